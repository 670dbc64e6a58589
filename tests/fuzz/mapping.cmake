curette_fuzzer(mapping ${R}/input/mapping.cpp ${R}/input/device_state.cpp)
