#pragma once
// What one frame asks of the renderer: the view, the shading mode and the ray-casting settings. Plain
// values (Dear ImGui style: one place to read each setting); the scene file and the viewer fill them.

#include "render/model/camera.h"
#include "render/model/shading_mode.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace curette {

// The shaders take this many lights (phong.glsl MAX_LIGHTS, ismos_occlusion.comp MAX_ISMOS_LIGHTS; the
// ShaderConstants test holds them equal).
inline constexpr int kMaxLights = 4;

struct Light {
    glm::dvec3 direction{0.3, 0.5, 1.0};  // towards the light; camera space is (right, up, towards viewer)
    glm::dvec3 color{1.0};                // colour times intensity
    bool cameraSpace = true;              // a headlight-style light moves with the camera
    bool operator==(const Light&) const = default;
};

// ISMOS (seed 003 sections 3.2, 3.7): the shape of light i of the frame (IsmosSettings::lightShapes[i]): its
// disk radius d in the texture-space box (negative: IsmosSettings::diskRadius) and, when spotAngleDeg > 0,
// a spotlight of half-angle omega aimed at spotTarget (world mm; nullopt: the volume's centre).
struct IsmosLightShape {
    double diskRadius = -1.0;
    double spotAngleDeg = 0.0;
    std::optional<glm::dvec3> spotTarget;
    bool operator==(const IsmosLightShape&) const = default;
};

// Cut faces: where a ray leaves a clip mesh (shaders/raycast.comp, dos_slice.comp, shade_sample.glsl;
// Weiskopf, Engel and Ertl 2003, sec. 5). The first sample behind the face lies on the face, standing for the
// ray from there with its partial length, so every mode reads colour, opacity and V_AO at the boundary;
// phong lights the tissue seen through the face with the clip surface's normal (mesh/surface_normals.h) until
// the ray has gathered normalOpacity of its opacity behind the face or passed half of normalDepthMm, then
// fades into the volume gradient by full opacity or normalDepthMm. Off: the lattice alone (for comparison).
struct CutFaceSettings {
    bool enabled = true;
    double normalDepthMm = 10.0;
    double normalOpacity = 0.9;
    bool operator==(const CutFaceSettings&) const = default;
};

struct RaycastSettings {
    double stepMm = 0.0;                  // 0: half the smallest voxel spacing
    double earlyTerminationAlpha = 0.99;  // stop a ray once its opacity reaches this
    std::uint32_t jitterSeed = 0;         // 0: no jitter; otherwise a deterministic per-pixel offset
    bool skipEmptySpace = true;
    CutFaceSettings cutFace;
    bool operator==(const RaycastSettings&) const = default;
};

// Directional occlusion shading (seed 001) and the slab pass.
struct DosSettings {
    double coneAngleDeg = 60.0;   // theta of the cone phase function (eq. 6); the paper shows 25-85 degrees
    int gridSize = 3;             // n: n x n samples on the cone base (eq. 13-15); 1 = no blur
    double sliceDistanceMm = 0.0; // d; 0: half the smallest voxel spacing
    double ambientRadiance = 1.0; // La
    bool operator==(const DosSettings&) const = default;
};

// Image-space multidirectional occlusion shading (seed 003), the `ismos` mode. Units of the radii are those
// of the paper's texture-space box: x, y span the image, z = 1 - depth spans the volume's bounding sphere.
// Defaults (the paper gives none):
//  - R = 2: every light centre lies outside the box (its farthest corner is 1.22 from (0.5, 0.5, 0)), so a
//    light is nearly directional (its direction varies by <= 17 degrees over the box) and matches the phong
//    base's light direction;
//  - d = 0.2: a penumbra of atan(0.2 / 2) = 5.7 degrees half-angle, soft but still a shadow (0 = hard);
//  - N = 16 light samples: 17 grey levels across a penumbra, below what 8 bit shows as banding after I_amb;
//  - N_R = 32 test points: a step of 1/32 of the box, about 2 voxels of a 64-voxel volume, 4 of a 128 one;
//    thinner occluders than that can be missed (the paper's Fig. 4a);
//  - I_amb = 0.3: a fully shadowed pixel keeps 30 %, about the TF materials' ambient term, so shadows never
//    go black and the phong base's ambient-only look is kept;
//  - alpha_th = 0.5: a layer counts as opaque when it stops half the light;
//  - depth bias 0.01 (1 % of the depth range): a surface does not shadow itself through the step between
//    its own layer depth and the next pixel's.
struct IsmosSettings {
    bool partial = true;            // partial occlusion (eq. 4-5); false: full occlusion (eq. 1-3)
    bool fit = false;               // partial: opacity from the transmittance fit (eq. 6-12); false: exact layers
    int layers = 4;                 // depth layers recorded by pass 1 (1-4, sec. 3.6)
    bool blendLayers = true;        // layers > 1: occlusion on every layer, blended front to back (Fig. 7d);
                                    // false: on the first layer above opacityThreshold only (Fig. 7c)
    int lightSamples = 16;          // N per light
    int testPoints = 32;            // N_R per path
    double hemisphereRadius = 2.0;  // R
    double diskRadius = 0.2;        // d, for lights without their own
    double ambient = 0.3;           // I_amb
    double opacityThreshold = 0.5;  // alpha_th
    double depthBias = 0.01;
    bool falloff = false;           // I_L ~ 1 / |L_c - P|^2 (normalised to 1 at the box centre)
    bool sphere = false;            // lights on a sphere around (0.5, 0.5, 0.5) (may sit behind the volume)
    ShadingMode base = ShadingMode::Phong;   // the colour ISMOS shades over: phong (the paper's LI) or solid
    std::vector<IsmosLightShape> lightShapes;  // per light of the frame; missing entries: the defaults
    bool operator==(const IsmosSettings&) const = default;
};

struct FrameDescription {
    OrbitCamera camera;
    glm::ivec2 size{512, 512};
    ShadingMode shading = ShadingMode::Phong;
    RaycastSettings raycast;
    DosSettings dos;
    IsmosSettings ismos;
    std::vector<Light> lights{Light{}};
    bool operator==(const FrameDescription&) const = default;
};

// Whether the slab pass runs (and so the DOS cone and grid shape the image) for `shading`, with or without
// tubes in view: planFrame decides, and the viewer's panel asks here.
bool slabPassRuns(ShadingMode shading, bool tubesInView);

// A light's direction in world space (camera-space lights are (right, up, towards the viewer)), unit length.
glm::dvec3 worldLightDirection(const Light& light, const OrbitCamera& camera);

}  // namespace curette
