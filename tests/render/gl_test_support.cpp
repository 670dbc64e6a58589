#include "tests/render/gl_test_support.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

namespace curette::test {

gl::Context& glContext() {
    static std::unique_ptr<gl::Context> context = gl::createHeadlessContext();
    context->makeCurrent();
    return *context;
}

VolumeData makeVolume(glm::ivec3 dims, const glm::dmat4& indexToWorld, ScalarType type,
                      const std::function<double(glm::dvec3)>& f) {
    std::size_t n = static_cast<std::size_t>(dims.x) * static_cast<std::size_t>(dims.y) * static_cast<std::size_t>(dims.z);
    std::vector<std::uint8_t> bytes(n * scalarTypeSize(type));
    std::size_t index = 0;
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i, ++index) {
                double v = f(glm::dvec3(indexToWorld * glm::dvec4(i, j, k, 1.0)));
                if (type == ScalarType::UInt8) {
                    bytes[index] = static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 255.0)));
                } else if (type == ScalarType::Float32) {
                    float x = static_cast<float>(v);
                    std::memcpy(bytes.data() + 4 * index, &x, 4);
                } else if (type == ScalarType::Int16) {
                    auto x = static_cast<std::int16_t>(std::lround(std::clamp(v, -32768.0, 32767.0)));
                    std::memcpy(bytes.data() + 2 * index, &x, 2);
                }
            }
    return buildVolume("<synthetic>", dims, type, bytes.data(), false, 1.0, 0.0, indexToWorld);
}

glm::dmat4 centredAffine(glm::ivec3 dims, glm::dvec3 spacing) {
    glm::dmat4 m(1.0);
    for (int a = 0; a < 3; ++a) m[a][a] = spacing[a];
    m[3] = glm::dvec4(-0.5 * glm::dvec3(dims - 1) * spacing, 1.0);
    return m;
}

TransferFunction rampTransferFunction(double lo, double hi, double alpha) {
    TransferFunction tf;
    tf.name = "test ramp";
    tf.color = {{0.0, glm::dvec3(0.2, 0.3, 0.4)}, {255.0, glm::dvec3(1.0, 0.9, 0.8)}};
    tf.opacity = {{0.0, 0.0}, {lo, 0.0}, {hi, alpha}, {255.0, alpha}};
    return tf;
}

double blobField(glm::dvec3 p) {
    const glm::dvec4 centres[] = {{-6, -4, 2, 9}, {7, 5, -3, 7}, {2, -8, -6, 5}, {-3, 9, 8, 6}};
    double v = 0;
    for (const glm::dvec4& c : centres) v += 230.0 * std::exp(-glm::dot(p - glm::dvec3(c), p - glm::dvec3(c)) / (2 * c.w * c.w));
    return std::min(v, 255.0);
}

}  // namespace curette::test
