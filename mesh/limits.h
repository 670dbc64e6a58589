#pragma once
// Limits of the clip-mesh set that code without GL needs too (the interaction state, the scene reader).

namespace curette::clip {

inline constexpr int kMaxClipMeshes = 16;   // shaders/clip_test.glsl MAX_CLIP_MESHES

}  // namespace curette::clip
