#pragma once
// The transfer function baked for the GPU: a 1D RGBA32F table over the TF's value range (colour, opacity
// per unit length), a 1D table of the gradient-opacity factor, and the maps from stored texel values to
// table coordinates. Also answers "can any sample with texel values in [lo, hi] be non-transparent?" for
// empty-space skipping, from the same table the shader filters.
//
// Layout of the table: `domainTexels` texels over the TF's domain [d0, d1] (the first and last centres on
// d0 and d1). Only for a volume with no-data voxels (a scene allocates what it uses, and every other volume
// keeps the plain table bit for bit) they are preceded by `leadTexels` more at the same spacing that continue the first point's colour and
// opacity down to d0 - 3 (d1 - d0) (the TF's clamping), except the very first texel, whose opacity is 0.
// With clamp-to-edge, every value below that point is therefore transparent: that is where volumes store
// voxels without data (NaN/Inf in the file, base/volume.h noDataTexelBelow), so "no data" costs the shader
// nothing. Data more than three domain widths below a TF's first point become transparent too; that differs
// from the TF's own clamping only for a TF whose first point has opacity, which no shipped TF has.

#include "gl/objects.h"
#include "gl/program.h"
#include "base/transfer_function.h"
#include "render/label_overlay.h"
#include "render/removal_texture.h"

#include <vector>

namespace curette {

class TransferFunctionTexture {
public:
    static constexpr int domainTexels = 4096;
    static constexpr int leadTexels = 3 * (domainTexels - 1) + 3;  // texel 0 at d0 - (3 + 3/4095) (d1 - d0)
    static constexpr int noDataTableSize = leadTexels + domainTexels;   // 16384, GL 4.5's smallest GL_MAX_TEXTURE_SIZE
    static constexpr int gradientTableSize = 256;

    // valueScale/valueOffset: the volume's texel -> physical value map.
    // noData: the volume stores voxels without data below its minimum (base/volume.h): add the transparent lead.
    TransferFunctionTexture(const TransferFunction& tf, double valueScale, double valueOffset, bool noData = false);
    int tableSize() const { return static_cast<int>(table_.size()); }
    int leadTexelCount() const { return lead_; }

    GLuint texture() const { return texture_.name(); }
    GLuint gradientTexture() const { return gradientTexture_.name(); }
    glm::vec2 texelToTf() const { return texelToTf_; }
    glm::vec2 gradientToTf() const { return gradientToTf_; }
    bool useGradientOpacity() const { return useGradientOpacity_; }
    float unitLengthMm() const { return unitLengthMm_; }
    const TransferFunction::Material& material() const { return material_; }
    const std::vector<glm::vec4>& table() const { return table_; }

    // The binder of shaders/transfer_function.glsl: adds the defines it needs (GRADIENT_OPACITY when the TF
    // has one) to `defines`; apply() sets its uniforms on a program compiled with them and binds the tables.
    // With label volumes attached, classification includes them (shaders/labels.glsl): the defines and
    // bindings of the LabelOverlay come along, so no pass that classifies can forget them.
    void addDefines(gl::Defines& defines) const;
    // A ray caster's lattice step of `stepMm`: STEP_OPACITY_ROOTS n where step / unit length, as the shader's
    // float, is 2^-n (n = 0, 1, 2), so correctStepOpacity takes n square roots instead of pow.
    void addStepDefines(gl::Defines& defines, double stepMm) const;
    void apply(gl::Program& program) const;
    void attachLabels(const LabelOverlay* labels) { labels_ = labels; }
    // The drilled removal (shaders/drill_removal.glsl) comes along the same way.
    void attachRemoval(const RemovalTexture* removal) { removal_ = removal; }

    // Largest opacity the linearly filtered table returns for texel values in [lo, hi] (with one table
    // texel of margin for rounding of the coordinate on the GPU).
    float maxOpacity(float texelLo, float texelHi) const;

private:
    gl::Texture texture_, gradientTexture_;
    std::vector<glm::vec4> table_;
    std::vector<std::vector<float>> sparseMax_;  // sparse table: level l holds max over 2^l texels
    glm::vec2 texelToTf_{1, 0}, gradientToTf_{0, 0};
    bool useGradientOpacity_ = false;
    float unitLengthMm_ = 1;
    int lead_ = 0;
    TransferFunction::Material material_;
    const LabelOverlay* labels_ = nullptr;
    const RemovalTexture* removal_ = nullptr;
};

}  // namespace curette
