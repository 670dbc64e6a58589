#pragma once
// The defines and uniforms of shaders/phong.glsl (the light count; lights in world space, material), set the
// same way for every pass that shades: the ray caster, the slab pass and the tube compositor.

#include "render/model/frame.h"
#include "gl/program.h"
#include "base/transfer_function.h"

namespace curette {

// The lights phong.glsl takes of a frame (at most kMaxLights).
int shadedLightCount(const FrameDescription& frame);
// LIGHT_COUNT: a program variant per light count (phong.glsl says why).
void addLightingDefines(gl::Defines& defines, const FrameDescription& frame);
void setLightingUniforms(gl::Program& program, const FrameDescription& frame, const TransferFunction::Material& material);

}  // namespace curette
