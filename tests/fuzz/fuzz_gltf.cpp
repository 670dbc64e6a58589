// libFuzzer target: glTF 2.0 (.gltf JSON and .glb) clip meshes: tinygltf parsing, then our accessor bounds
// checks, node walk, welding and closedness validation.
#include "base/error.h"
#include "mesh/gltf_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        curette::clip::loadGltfFromMemory(std::span(data, size), "fuzz.gltf", 1.0);
    } catch (const curette::InputError&) {
    }
    return 0;
}
