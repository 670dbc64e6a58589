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
    float depthMap[4];   // xy: depth offset, z: depth scale, w: depth resolution (ClippingCamera::depthOffset)
};
static_assert(sizeof(CameraGpu) == 160);

}  // namespace curette::clip
