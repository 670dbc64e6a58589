#pragma once
// The uniforms of shaders/phong.glsl (lights in world space, material), set the same way for every pass that
// shades: the ray caster, the slab pass and the tube compositor.

#include "render/frame.h"
#include "gl/program.h"
#include "base/transfer_function.h"

namespace curette {

// A light's direction in world space (camera-space lights are (right, up, towards the viewer)), unit length.
glm::dvec3 worldLightDirection(const Light& light, const OrbitCamera& camera);

void setLightingUniforms(gl::Program& program, const FrameDescription& frame, const TransferFunction::Material& material);

}  // namespace curette
