// Sampling the data volume. Texture coordinates come from world millimetres through one matrix,
// worldToTexture, derived from the volume's inverse affine in render/model/volume_geometry.cpp (the only
// place that derives it). Texture (0,0,0)..(1,1,1) spans voxel cells, so voxel (i,j,k)'s
// centre is at ((i,j,k) + 0.5) / dims.
#include "bindings.glsl"
#include "no_data.glsl"
#include "volume_layout.glsl"

layout(binding = BINDING_VOLUME) uniform sampler3D volumeData;
uniform mat4 worldToTexture;
uniform vec3 texelSize;            // 1 / dims
uniform mat3 gradientToWorld;      // transpose(inverse(linear part of indexToWorld)) * valueScale

vec3 toTexture(vec3 world) { return (worldToTexture * vec4(world, 1.0)).xyz; }

// The stored value as the GPU filters it (normalized for UNorm formats).
float sampleTexel(vec3 tex) { return VOLUME_SAMPLE(volumeData, tex).r; }

#ifdef GRADIENT_VOLUME
// The same central differences, per voxel, interpolated (render/gradient_volume.h): one read instead of six.
layout(binding = BINDING_GRADIENT_VOLUME) uniform sampler3D gradientVolume;
uniform vec3 gradientVolumeScale, gradientVolumeOffset;   // the volume's texture coordinate -> the padded texture's
uniform float gradientVolumeUnit;                         // a stored difference -> normalized value units

vec3 gradientWorld(vec3 tex) {
    vec3 d = texture(gradientVolume, tex * gradientVolumeScale + gradientVolumeOffset).xyz * gradientVolumeUnit;
    return gradientToWorld * (0.5 * d);
}
#else
// Gradient of the physical value in world units (value per mm), by central differences one voxel apart
// along each index axis (one-sided next to no data: no_data.glsl).
vec3 gradientWorld(vec3 tex) {
    vec3 minus = vec3(sampleTexel(tex - vec3(texelSize.x, 0, 0)), sampleTexel(tex - vec3(0, texelSize.y, 0)),
                      sampleTexel(tex - vec3(0, 0, texelSize.z)));
    vec3 plus = vec3(sampleTexel(tex + vec3(texelSize.x, 0, 0)), sampleTexel(tex + vec3(0, texelSize.y, 0)),
                     sampleTexel(tex + vec3(0, 0, texelSize.z)));
    vec3 d = differencesAcross(minus, vec3(sampleTexel(tex)), plus);  // the centre: read only with NO_DATA
    return gradientToWorld * (0.5 * d);
}
#endif
