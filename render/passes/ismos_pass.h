#pragma once
// The ISMOS passes (seed 003): pass 1 is the ray caster compiled with ISMOS_LAYERS (shaders/ismos_layers.glsl
// records the layers and the fit beside the colour), pass 2 is shaders/ismos_occlusion.comp. This class owns
// what they add: the layer images (only those the variant uses), the light samples (rebuilt only when a
// light, the camera or the ISMOS settings change) and pass 2's program variants; it is the binder of both
// shader pieces.

#include "gl/objects.h"
#include "gl/program.h"
#include "render/model/frame.h"
#include "render/model/gpu_resources.h"
#include "render/model/ismos_model.h"

#include <optional>
#include <vector>

namespace curette {

class IsmosPass {
public:
    // Pass 1: the defines of the ray caster's ISMOS variant.
    static void addLayerDefines(gl::Defines& defines, const IsmosSettings& settings);
    // Pass 1: allocates the layer images for `size` and the variant, binds them and sets ismos_layers.glsl's
    // uniforms. `stepMm`: the ray caster's step.
    void applyLayers(gl::Program& program, const FrameDescription& frame, const IsmosSpace& space, double stepMm);
    // Pass 2 on `output` (RGBA32F, the ray caster's image), in place.
    void runOcclusion(const FrameDescription& frame, const IsmosSpace& space, glm::dvec3 volumeCentre, GLuint output);

    // Times the light samples were rebuilt (tests: only when a light or the camera moves).
    int lightRebuilds() const { return lightRebuilds_; }
    const std::vector<IsmosLight>& lights() const { return lights_; }
    IsmosLayerImages readLayers() const;
    // The bench's colour reference: when on, pass 2 first reads back the colour pass 1 (and the tube
    // compositor) left, C_p of eq. 3 (CPU memory only; nothing is allocated on the GPU).
    void capturePass1Colour(bool on) {
        capture_ = on;
        if (!on) pass1Colour_.clear();
    }
    const std::vector<glm::vec4>& pass1Colour() const { return pass1Colour_; }   // row 0 at the top
    std::vector<GpuAllocation> allocations() const;

private:
    void ensureImages(glm::ivec2 size, const IsmosSettings& settings);
    void updateLights(const FrameDescription& frame, const IsmosSpace& space, glm::dvec3 volumeCentre);

    glm::ivec2 size_{0};
    bool exact_ = false, fit_ = false;
    gl::Texture front_, alpha_, back_, beta_;
    gl::Buffer samples_;
    std::size_t sampleBytes_ = 0;
    std::vector<IsmosLight> lights_;
    struct LightKey {
        std::vector<Light> lights;
        OrbitCamera camera;
        glm::ivec2 size;
        IsmosSettings settings;
        glm::dvec3 centre;
        bool operator==(const LightKey&) const = default;
    };
    std::optional<LightKey> lightKey_;
    int lightRebuilds_ = 0;
    bool capture_ = false;
    std::vector<glm::vec4> pass1Colour_;
    double stepDepth_ = 0;
    gl::ComputeVariants programs_{"ismos_occlusion.comp"};
};

}  // namespace curette
