curette_fuzzer(session ${R}/app/session.cpp ${R}/input/mapping.cpp ${R}/input/device_state.cpp ${R}/input/raw_reports.cpp
               ${R}/render/shading_mode.cpp)
