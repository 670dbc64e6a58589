curette_fuzzer(tck ${R}/app/io/tract_file.cpp ${R}/render/tractogram.cpp)
