curette_fuzzer(tf_json ${R}/app/io/transfer_function_file.cpp)
