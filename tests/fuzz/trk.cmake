curette_fuzzer(trk ${R}/app/io/tract_file.cpp ${R}/render/tractogram.cpp)
