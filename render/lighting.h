#pragma once
// The uniforms of shaders/phong.glsl (lights in world space, material), set the same way for every pass that
// shades: the ray caster, the slab pass and the tube compositor.

#include "render/model/frame.h"
#include "gl/program.h"
#include "base/transfer_function.h"

namespace curette {

void setLightingUniforms(gl::Program& program, const FrameDescription& frame, const TransferFunction::Material& material);

}  // namespace curette
