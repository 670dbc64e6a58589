curette_fuzzer(vp ${R}/app/io/transfer_function_file.cpp)
