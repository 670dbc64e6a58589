#include "render/transfer_function_texture.h"

#include "gl/bindings.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

namespace curette {

TransferFunctionTexture::TransferFunctionTexture(const TransferFunction& tf, double valueScale, double valueOffset, bool noData)
    : unitLengthMm_(static_cast<float>(tf.unitLengthMm)), lead_(noData ? leadTexels : 0), material_(tf.material) {
    const int tableSize = lead_ + domainTexels;
    // Table texel leadTexels + i holds the TF at value d0 + i/(N-1) * (d1-d0), N = domainTexels, so the
    // domain's first and last texel centres sit exactly on the TF's end points; the lead texels below continue
    // the TF's clamped first value at the same spacing, and texel 0 is transparent (the header's layout).
    double d0 = tf.domainMin(), d1 = tf.domainMax();
    if (d1 <= d0) d1 = d0 + 1.0;
    double spacing = (d1 - d0) / (domainTexels - 1);
    table_.resize(tableSize);
    for (int i = 0; i < tableSize; ++i) {
        double v = i < lead_ ? d0 - (lead_ - i) * spacing : d0 + (d1 - d0) * (i - lead_) / (domainTexels - 1);
        table_[static_cast<std::size_t>(i)] = glm::vec4(glm::vec3(tf.evaluateColor(v)), static_cast<float>(tf.evaluateOpacity(v)));
    }
    if (lead_ > 0) {
        table_[0].a = 0.0f;  // no data, and anything else this far below the first point
        // coordinate = (lead + 0.5 + (value - d0) / spacing) / tableSize, value = scale * texel + offset.
        double perValue = 1.0 / (spacing * tableSize);
        texelToTf_ = glm::vec2(static_cast<float>(valueScale * perValue),
                               static_cast<float>((lead_ + 0.5) / tableSize + (valueOffset - d0) * perValue));
    } else {
        // coordinate = (0.5 + (value - d0) / (d1 - d0) * (N - 1)) / N: the plain table, written as it always was
        // so images of volumes without no-data voxels stay bit-identical.
        double perValue = (tableSize - 1) / ((d1 - d0) * tableSize);
        texelToTf_ = glm::vec2(static_cast<float>(valueScale * perValue),
                               static_cast<float>(0.5 / tableSize + (valueOffset - d0) * perValue));
    }

    texture_ = gl::createTexture(GL_TEXTURE_1D);
    glTextureStorage1D(texture_.name(), 1, GL_RGBA32F, tableSize);
    glTextureSubImage1D(texture_.name(), 0, 0, tableSize, GL_RGBA, GL_FLOAT, table_.data());
    glTextureParameteri(texture_.name(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture_.name(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture_.name(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glObjectLabel(GL_TEXTURE, texture_.name(), -1, "transfer function");

    // Gradient opacity over [0, last point]; beyond it the last value holds.
    useGradientOpacity_ = tf.hasGradientOpacity();
    std::vector<float> gradientTable(gradientTableSize, 1.0f);
    double g1 = tf.gradientOpacity.empty() ? 1.0 : std::max(tf.gradientOpacity.back().value, 1e-9);
    for (int i = 0; i < gradientTableSize; ++i)
        gradientTable[static_cast<std::size_t>(i)] =
            static_cast<float>(tf.evaluateGradientOpacity(g1 * i / (gradientTableSize - 1)));
    double perGradient = (gradientTableSize - 1) / (g1 * gradientTableSize);
    gradientToTf_ = glm::vec2(static_cast<float>(perGradient), 0.5f / gradientTableSize);
    gradientTexture_ = gl::createTexture(GL_TEXTURE_1D);
    glTextureStorage1D(gradientTexture_.name(), 1, GL_R32F, gradientTableSize);
    glTextureSubImage1D(gradientTexture_.name(), 0, 0, gradientTableSize, GL_RED, GL_FLOAT, gradientTable.data());
    glTextureParameteri(gradientTexture_.name(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(gradientTexture_.name(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(gradientTexture_.name(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);

    // Sparse table for range-maximum queries of opacity in O(1).
    std::vector<float> level(tableSize);
    for (int i = 0; i < tableSize; ++i) level[static_cast<std::size_t>(i)] = table_[static_cast<std::size_t>(i)].a;
    sparseMax_.push_back(level);
    for (int span = 1; 2 * span <= tableSize; span *= 2) {
        const std::vector<float>& previous = sparseMax_.back();
        std::vector<float> next(tableSize - 2 * span + 1);
        for (std::size_t i = 0; i < next.size(); ++i) next[i] = std::max(previous[i], previous[i + static_cast<std::size_t>(span)]);
        sparseMax_.push_back(std::move(next));
    }
}

float TransferFunctionTexture::maxOpacity(float texelLo, float texelHi) const {
    // Texel coordinate of a value: u * N - 0.5; linear filtering reads floor and floor + 1.
    // Clamped before the conversion to int: a no-data texel value lies millions of table widths away.
    const int tableSize = this->tableSize();
    const float size = static_cast<float>(tableSize);
    auto texelIndex = [&](float texel) {
        return std::clamp((texel * texelToTf_.x + texelToTf_.y) * size - 0.5f, -4.0f, size + 4.0f);
    };
    float a = texelIndex(texelLo), b = texelIndex(texelHi);
    if (a > b) std::swap(a, b);  // a negative scale reverses the order
    int lo = std::clamp(static_cast<int>(std::floor(a)) - 1, 0, tableSize - 1);
    int hi = std::clamp(static_cast<int>(std::floor(b)) + 2, 0, tableSize - 1);
    int level = std::bit_width(static_cast<unsigned>(hi - lo + 1)) - 1;
    const std::vector<float>& row = sparseMax_[static_cast<std::size_t>(level)];
    return std::max(row[static_cast<std::size_t>(lo)], row[static_cast<std::size_t>(hi - (1 << level) + 1)]);
}

void TransferFunctionTexture::addDefines(gl::Defines& defines) const {
    if (useGradientOpacity_) defines.emplace_back("GRADIENT_OPACITY", "1");
    if (labels_) labels_->addDefines(defines);
    if (removal_) removal_->addDefines(defines);
}

void TransferFunctionTexture::addStepDefines(gl::Defines& defines, double stepMm) const {
    // The exponent as the shader forms it (float step over float unit length), so a root stands in only where
    // pow's exponent is exactly 1, 1/2 or 1/4.
    float exponent = static_cast<float>(stepMm) / unitLengthMm_;
    for (int roots = 0; roots <= 2; ++roots)
        if (exponent == std::ldexp(1.0f, -roots)) defines.emplace_back("STEP_OPACITY_ROOTS", std::to_string(roots));
}

void TransferFunctionTexture::apply(gl::Program& p) const {
    p.set("texelToTf", texelToTf_);
    p.set("gradientToTf", gradientToTf_);
    p.set("tfUnitLengthMm", unitLengthMm_);
    glBindTextureUnit(binding::transferFunction, texture_.name());
    glBindTextureUnit(binding::gradientOpacity, gradientTexture_.name());
    if (labels_) labels_->apply(p);
    if (removal_) removal_->apply(p);
}

}  // namespace curette
