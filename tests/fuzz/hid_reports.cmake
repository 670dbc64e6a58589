curette_fuzzer(hid_reports ${R}/input/devices/parsers.cpp ${R}/input/device_state.cpp)
