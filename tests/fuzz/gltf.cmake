find_package(TinyGLTF REQUIRED)
curette_fuzzer(gltf ${R}/clip/gltf_mesh.cpp ${R}/clip/triangle_mesh.cpp)
target_link_libraries(fuzz_gltf PRIVATE TinyGLTF::TinyGLTF)
