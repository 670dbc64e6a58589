#pragma once
// What one frame asks of the renderer: the view, the shading mode and the ray-casting settings. Plain
// values (Dear ImGui style: one place to read each setting); the scene file and the viewer fill them.

#include "render/camera.h"
#include "render/shading_mode.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace curette {

struct Light {
    glm::dvec3 direction{0.3, 0.5, 1.0};  // towards the light; camera space is (right, up, towards viewer)
    glm::dvec3 color{1.0};                // colour times intensity
    bool cameraSpace = true;              // a headlight-style light moves with the camera
    bool operator==(const Light&) const = default;
};

struct RaycastSettings {
    double stepMm = 0.0;                  // 0: half the smallest voxel spacing
    double earlyTerminationAlpha = 0.99;  // stop a ray once its opacity reaches this
    std::uint32_t jitterSeed = 0;         // 0: no jitter; otherwise a deterministic per-pixel offset
    bool skipEmptySpace = true;
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

struct FrameDescription {
    OrbitCamera camera;
    glm::ivec2 size{512, 512};
    ShadingMode shading = ShadingMode::Phong;
    RaycastSettings raycast;
    DosSettings dos;
    std::vector<Light> lights{Light{}};
    bool operator==(const FrameDescription&) const = default;
};

}  // namespace curette
