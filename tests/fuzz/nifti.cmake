curette_fuzzer(nifti ${R}/app/io/nifti.cpp ${R}/app/io/gzip.cpp)
