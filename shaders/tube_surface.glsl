// Tubes in the ray cast (raycast.comp with TUBES; every mode without a slab pass: solid, phong, lao, cao). The
// ray stops in front of the pixel's tube surface (the G-buffer's view depth), and the surface, lit by the mode's
// own light, lies behind the volume composited in front of it (docs/subsystems.md "Tubes in the ray cast"):
//  - solid: the tube's flat colour, as a volume sample's is its TF colour;
//  - phong: Blinn-Phong (phong.glsl's terms, the tubes' own material) with the G-buffer normal; lines are lit
//    as illuminated lines (seed 004 eq. 3.12-3.15);
//  - lao/cao: the same, times V_AO read trilinearly at the surface point: the volume shadows the tubes in data
//    space, as the slab pass's partial occlusion did (seed 000 Algorithm 6 with V_AO for the occlusion term).
// Mirrored by reference::shadeTubeSurface (render/reference/raycast_reference.h). Binder: TubeSurfacePiece (render/shader_pieces.h).
#include "illuminated_lines.glsl"

layout(binding = BINDING_TUBE_DEPTH) uniform sampler2D tubeDepth;     // view depth of the nearest tube (0: none)
layout(binding = BINDING_TUBE_COLOR) uniform sampler2D tubeColor;
layout(binding = BINDING_TUBE_NORMAL) uniform sampler2D tubeNormal;   // world normal (tubes) or tangent (lines), w: kind
uniform vec4 tubeMaterial;             // ambient, diffuse, specular, specular power (TubeShading::material)
uniform float tubeLineDiffuseExponent; // p of seed 004 eq. 3.15
uniform vec3 tubeViewForward;          // the camera's unit forward: view depth = t * dot(direction, forward)

// The ray parameter (mm from the eye) of the pixel's tube surface, or a negative number without one.
float tubeRayT(ivec2 pixel, vec3 direction) {
    float view = texelFetch(tubeDepth, pixel, 0).r;
    return view > 0.0 ? view / dot(direction, tubeViewForward) : -1.0;
}

// The lit colour of the tube surface at ray parameter t (premultiplied, opaque).
vec3 shadeTubeSurface(ivec2 pixel, vec3 direction, float t) {
    vec3 albedo = texelFetch(tubeColor, pixel, 0).rgb;
#if SHADING == SHADING_SOLID
    return albedo;
#else
    vec4 normalKind = texelFetch(tubeNormal, pixel, 0);
    vec3 toViewer = -direction;
    vec3 diffuse = vec3(0.0), specular = vec3(0.0);
    if (normalKind.w == SURFACE_TUBE) {
        vec3 n = normalize(normalKind.xyz);
        if (dot(n, toViewer) < 0.0) n = -n;
        for (int i = 0; i < lightCount; ++i) {
            vec2 terms = blinnPhongTerms(n, lightDirection[i], toViewer, tubeMaterial.w);
            diffuse += lightColor[i] * terms.x;
            specular += lightColor[i] * terms.y;
        }
    } else {
        vec3 tangent = normalize(normalKind.xyz);
        for (int i = 0; i < lightCount; ++i) {
            vec2 terms = illuminatedLineTerms(tangent, lightDirection[i], toViewer, tubeLineDiffuseExponent, tubeMaterial.w);
            diffuse += lightColor[i] * terms.x;
            specular += lightColor[i] * terms.y;
        }
    }
    float occlusion = 1.0;
#if SHADING == SHADING_LAO || SHADING == SHADING_CAO
    occlusion = texture(ambientOcclusion, toTexture(eyeWorld + t * direction)).r;
#endif
    return occlusion * albedo * (tubeMaterial.x + tubeMaterial.y * diffuse) + tubeMaterial.z * specular;
#endif
}
