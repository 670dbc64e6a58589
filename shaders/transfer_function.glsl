// Classification: the transfer function maps a data value to colour and to opacity per unit length; the
// opacity of a segment is then corrected for its length (render/transfer_function.h).
#include "bindings.glsl"
#include "labels.glsl"
#include "drill_removal.glsl"

layout(binding = BINDING_TRANSFER_FUNCTION) uniform sampler1D transferFunction;
layout(binding = BINDING_GRADIENT_OPACITY) uniform sampler1D gradientOpacity;
uniform vec2 texelToTf;             // tf coordinate = texel * texelToTf.x + texelToTf.y
uniform vec2 gradientToTf;          // gradient-opacity coordinate = |gradient| * x + y
uniform float tfUnitLengthMm;       // opacity in the TF is that of a slab this thick
// Compiled in or out (TransferFunctionTexture::addDefines), not a uniform: on llvmpipe a uniform switch would
// still pay for the six gradient fetches of every sample (render/gl/program.h, ComputeVariants).
#ifdef GRADIENT_OPACITY
const bool useGradientOpacity = true;
#else
const bool useGradientOpacity = false;
#endif

// rgb and opacity per unit length at a stored texel value.
vec4 classify(float texel) { return texture(transferFunction, texel * texelToTf.x + texelToTf.y); }

float gradientOpacityFactor(float gradientMagnitude) {
    return texture(gradientOpacity, gradientMagnitude * gradientToTf.x + gradientToTf.y).r;
}

// Opacity of a segment `lengthMm` long through a medium of opacity `alphaUnit` per tfUnitLengthMm:
// 1 - (1 - a)^(d / d0), the exact product of transmittances of d/d0 unit slabs.
float correctOpacity(float alphaUnit, float lengthMm) {
    return 1.0 - pow(max(1.0 - alphaUnit, 0.0), lengthMm / tfUnitLengthMm);
}

// The same for a ray caster's lattice step, `stepMm` long. Where the exponent stepMm / tfUnitLengthMm is 2^-n
// (STEP_OPACITY_ROOTS n, TransferFunctionTexture::addStepDefines), n square roots: on llvmpipe pow is exp2 of
// log2, and the head's solid ray cast took 12-15 % less time with one root (docs/measurements.md).
float correctStepOpacity(float alphaUnit, float stepMm) {
#ifndef STEP_OPACITY_ROOTS
    return correctOpacity(alphaUnit, stepMm);
#else
    float transmittance = max(1.0 - alphaUnit, 0.0);
#if STEP_OPACITY_ROOTS >= 1
    transmittance = sqrt(transmittance);
#endif
#if STEP_OPACITY_ROOTS >= 2
    transmittance = sqrt(transmittance);
#endif
    return 1.0 - transmittance;
#endif
}
