#version 450
// The gradient volume (render/gradient_volume.h says why it is phong's gradient): per texel the clamped central
// differences of the voxel it stands for, the texture one texel larger than the scan on every side.
#include "bindings.glsl"

layout(local_size_x = 8, local_size_y = 4, local_size_z = 2) in;
layout(binding = BINDING_VOLUME) uniform sampler3D volumeData;
layout(rgba16_snorm, binding = IMAGE_GRADIENT_VOLUME) uniform writeonly image3D gradientsOut;
uniform ivec3 volumeSize;
uniform float storeScale;   // kGradientStoreScale: a difference of k 8-bit steps is stored as 128 k (of 32767), exactly

float value(ivec3 v) { return texelFetch(volumeData, clamp(v, ivec3(0), volumeSize - 1), 0).r; }

void main() {
    ivec3 texel = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(texel, volumeSize + 2))) return;
    ivec3 v = texel - 1;   // the voxel it stands for (-1 and the size: the pad)
    vec3 d = vec3(value(v + ivec3(1, 0, 0)) - value(v - ivec3(1, 0, 0)), value(v + ivec3(0, 1, 0)) - value(v - ivec3(0, 1, 0)),
                  value(v + ivec3(0, 0, 1)) - value(v - ivec3(0, 0, 1)));
    imageStore(gradientsOut, texel, vec4(d * storeScale, 0.0));
}
