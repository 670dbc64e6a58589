// Blinn-Phong: one definition of the diffuse and specular terms for volume samples (`phong` shading) and tube
// surfaces (tube_composite.comp). Up to MAX_LIGHTS directional lights in world space.
// Binder: addLightingDefines and setLightingUniforms (render/lighting.h).
#define MAX_LIGHTS 4

// The number of lights is compiled in, so every loop over the lights unrolls: llvmpipe runs a loop with a
// uniform count under lane masks with its array reads indexed, which cost the glass brain's phong ray cast
// about a fifth of its time (docs/measurements.md). Each light count is its own program variant.
#ifndef LIGHT_COUNT
#error "phong.glsl needs LIGHT_COUNT (addLightingDefines)"
#endif
const int lightCount = LIGHT_COUNT;
uniform vec3 lightDirection[MAX_LIGHTS];   // world, unit, from the surface towards the light
uniform vec3 lightColor[MAX_LIGHTS];       // colour times intensity
uniform vec4 material;                     // ambient, diffuse, specular, specular power

// (n.l clamped, specular) for unit normal n, unit light direction l and unit view direction v.
vec2 blinnPhongTerms(vec3 n, vec3 l, vec3 v, float power) {
    float diffuse = max(dot(n, l), 0.0);
    vec3 halfway = normalize(l + v);
    float specular = diffuse > 0.0 ? pow(max(dot(n, halfway), 0.0), power) : 0.0;
    return vec2(diffuse, specular);
}

// albedo: TF colour; gradient: world gradient of the value; viewDirection: unit, from the sample to the eye;
// ambient: the ambient light reaching the sample (1 without occlusion).
vec3 shadePhong(vec3 albedo, vec3 gradient, vec3 viewDirection, float ambient) {
    float magnitude = length(gradient);
    vec3 color = material.x * ambient * albedo;
    // Homogeneous regions have no surface to light: they keep the ambient term and a flat diffuse term, so
    // the interior of a structure does not go black.
    if (magnitude < 1e-6) return color + material.y * albedo;
    vec3 normal = -gradient / magnitude;                       // points from dense to less dense
    if (dot(normal, viewDirection) < 0.0) normal = -normal;    // two-sided: light the side we see
    for (int i = 0; i < lightCount; ++i) {
        vec2 terms = blinnPhongTerms(normal, lightDirection[i], viewDirection, material.w);
        color += lightColor[i] * (material.y * terms.x * albedo + material.z * terms.y);
    }
    return color;
}
