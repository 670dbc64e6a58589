#pragma once
// One clip mesh's entry of the UBO_CLIP_MESHES block: the std140 layout of ClipMeshGpu in shaders/clip_test.glsl
// (the ShaderConstants test compares every member's offset and the size with the GLSL block).

#include <cstdint>

namespace curette::clip {

struct CameraGpu {
    float worldToMap[16];
    std::int32_t info[4];
    float mapBox[4];
    float depthBoxLo[4], depthBoxHi[4];
    float depthBall[4];
};
static_assert(sizeof(CameraGpu) == 144);

}  // namespace curette::clip
