curette_fuzzer(nrrd ${R}/app/io/nrrd.cpp ${R}/app/io/gzip.cpp)
