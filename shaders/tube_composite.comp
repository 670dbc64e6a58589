#version 450
// Final compositing with tubes (seed 000 Algorithms 5 and 6). For a pixel covered by a tube, the occlusion
// of the surface is the partial occlusion (volume and low-frequency geometry, from the slab pass) times the
// vicinity term (high-frequency geometry: the fraction of Poisson-disk neighbours within
// l_vicinity * tan(theta) that are not nearer to the eye than the surface plus a depth bias). The lit surface
// lies behind the volume accumulated in front of it in the eye buffer.
#include "bindings.glsl"
#include "pixel_ray.glsl"
#include "phong.glsl"
#include "illuminated_lines.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = IMAGE_OUTPUT) uniform image2D eyeBuffer;
layout(binding = BINDING_TUBE_DEPTH) uniform sampler2D tubeDepth;
layout(binding = BINDING_TUBE_COLOR) uniform sampler2D tubeColor;
layout(binding = BINDING_TUBE_NORMAL) uniform sampler2D tubeNormal;
layout(binding = BINDING_PARTIAL_OCCLUSION) uniform sampler2D partialOcclusionBuffer;
layout(std430, binding = SSBO_POISSON_DISK) readonly buffer PoissonDisk { vec2 poissonDisk[]; };

uniform int poissonCount;
uniform float vicinityRadiusPixelsAtUnitDepth;   // l_vicinity tan(theta) * pixels per mm at 1 mm depth
uniform float depthBiasMm;
uniform bool useOcclusion;                       // false in solid/phong shading: no occlusion terms
uniform float lineDiffuseExponent;               // p of eq. 3.15
uniform int firstRow;                            // the dispatch covers a band of rows from here (an exact frame in slices)

// Algorithm 5: 1 - (neighbours nearer than the biased surface depth) / samples.
float vicinityOcclusion(ivec2 pixel, float surfaceDepth) {
    float radius = vicinityRadiusPixelsAtUnitDepth / surfaceDepth;
    float biased = surfaceDepth - depthBiasMm;  // an occluder must be this much nearer to the eye
    int occluded = 0;
    for (int i = 0; i < poissonCount; ++i) {
        ivec2 q = clamp(pixel + ivec2(round(poissonDisk[i] * radius)), ivec2(0), outputSize - 1);
        float d = texelFetch(tubeDepth, q, 0).r;
        if (d > 0.0 && d < biased) ++occluded;
    }
    return 1.0 - float(occluded) / float(max(poissonCount, 1));
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy) + ivec2(0, firstRow);
    if (outsideImage(pixel)) return;
    vec4 normalKind = texelFetch(tubeNormal, pixel, 0);
    if (normalKind.w == SURFACE_NONE) return;  // the volume alone: the eye buffer is the pixel
    vec4 eye = imageLoad(eyeBuffer, pixel);
    float surfaceDepth = texelFetch(tubeDepth, pixel, 0).r;
    vec3 albedo = texelFetch(tubeColor, pixel, 0).rgb;
    float occlusion = useOcclusion ? texelFetch(partialOcclusionBuffer, pixel, 0).r * vicinityOcclusion(pixel, surfaceDepth) : 1.0;

    vec3 toViewer = -pixelRayDirection(pixel);
    vec3 shaded;
    if (normalKind.w == SURFACE_TUBE) {
        // Algorithm 6: occlusion * colour * (ambient + diffuse) + specular.
        vec3 n = normalKind.xyz;
        if (dot(n, toViewer) < 0.0) n = -n;
        vec3 diffuse = vec3(0.0), specular = vec3(0.0);
        for (int i = 0; i < lightCount; ++i) {
            vec2 terms = blinnPhongTerms(n, lightDirection[i], toViewer, material.w);
            diffuse += lightColor[i] * terms.x;
            specular += lightColor[i] * terms.y;
        }
        shaded = occlusion * albedo * (material.x + material.y * diffuse) + material.z * specular;
    } else {
        vec3 diffuse = vec3(0.0), specular = vec3(0.0);
        for (int i = 0; i < lightCount; ++i) {
            vec2 terms = illuminatedLineTerms(normalKind.xyz, lightDirection[i], toViewer, lineDiffuseExponent, material.w);
            diffuse += lightColor[i] * terms.x;
            specular += lightColor[i] * terms.y;
        }
        shaded = occlusion * albedo * (material.x + material.y * diffuse) + material.z * specular;
    }
    imageStore(eyeBuffer, pixel, vec4(shaded * (1.0 - eye.a) + eye.rgb, 1.0));
}
