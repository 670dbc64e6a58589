#pragma once
// The transfer function baked for the GPU: a 1D RGBA32F table over the TF's value range (colour, opacity
// per unit length), a 1D table of the gradient-opacity factor, and the maps from stored texel values to
// table coordinates. Also answers "can any sample with texel values in [lo, hi] be non-transparent?" for
// empty-space skipping, from the same table the shader filters.

#include "gl/objects.h"
#include "gl/program.h"
#include "base/transfer_function.h"

#include <vector>

namespace curette {

class TransferFunctionTexture {
public:
    static constexpr int tableSize = 4096;
    static constexpr int gradientTableSize = 256;

    // valueScale/valueOffset: the volume's texel -> physical value map.
    TransferFunctionTexture(const TransferFunction& tf, double valueScale, double valueOffset);

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
    void addDefines(gl::Defines& defines) const;
    void apply(gl::Program& program) const;

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
    TransferFunction::Material material_;
};

}  // namespace curette
