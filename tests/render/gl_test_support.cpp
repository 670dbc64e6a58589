#include "tests/render/gl_test_support.h"

#include "render/renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <numbers>
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

FrameDescription frameLookingAt(glm::dvec3 target, double distanceMm, double azimuthDeg, double elevationDeg, glm::ivec2 size,
                                ShadingMode shading) {
    FrameDescription f;
    f.camera.target = target;
    f.camera.distanceMm = distanceMm;
    f.camera.azimuthDeg = azimuthDeg;
    f.camera.elevationDeg = elevationDeg;
    f.camera.fovYDeg = 30;
    f.camera.nearMm = 1;
    f.camera.farMm = 1000;
    f.size = size;
    f.shading = shading;
    return f;
}

glm::dmat4 centredAffine(glm::ivec3 dims, glm::dvec3 spacing) {
    glm::dmat4 m(1.0);
    for (int a = 0; a < 3; ++a) m[a][a] = spacing[a];
    m[3] = glm::dvec4(-0.5 * glm::dvec3(dims - 1) * spacing, 1.0);
    return m;
}

LaoSettings lightLao(int samples) {
    LaoSettings lao;
    parseLaoPattern("14", lao.directions);
    lao.samples = samples;
    lao.stepMm = 1.0;
    lao.antiAliasingSamples = 16;
    return lao;
}

AmbientAndImage renderAmbientAndImage(Renderer& renderer, const FrameDescription& frame) {
    renderer.render(frame);
    const AmbientOcclusion* ao = usesAmbientOcclusion(frame.shading) ? renderer.ambientOcclusion() : nullptr;
    return {ao ? ao->readAmbient() : std::vector<std::uint16_t>{}, renderer.readImage()};
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

TubeVertices straightTube(glm::dvec3 centre, glm::dvec3 axis, double length, double radius, glm::vec4 color) {
    TubeVertices v;
    axis = glm::normalize(axis);
    glm::dvec3 u = glm::normalize(glm::cross(axis, std::abs(axis.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0)));
    glm::dvec3 w = glm::cross(axis, u);
    const int sides = 16, rings = 8;
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s < sides; ++s) {
            double a = 2 * std::numbers::pi * s / sides;
            glm::dvec3 n = std::cos(a) * u + std::sin(a) * w;
            v.positions.emplace_back(glm::vec3(centre + (double(r) / rings - 0.5) * length * axis + radius * n));
            v.directions.emplace_back(glm::vec3(n));
            v.colors.push_back(color);
        }
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < sides; ++s) {
            std::uint32_t a = static_cast<std::uint32_t>(r * sides + s), b = static_cast<std::uint32_t>(r * sides + (s + 1) % sides);
            std::uint32_t c = a + sides, d = b + sides;
            v.indices.insert(v.indices.end(), {a, b, d, a, d, c});
        }
    for (int end = 0; end < 2; ++end) {  // caps: a fan around a centre vertex
        std::uint32_t first = static_cast<std::uint32_t>(v.positions.size());
        glm::dvec3 n = end ? axis : -axis;
        v.positions.emplace_back(glm::vec3(centre + (end ? 0.5 : -0.5) * length * axis));
        v.directions.emplace_back(glm::vec3(n));
        v.colors.push_back(color);
        for (int s = 0; s < sides; ++s) {
            double a = 2 * std::numbers::pi * s / sides;
            v.positions.emplace_back(glm::vec3(centre + (end ? 0.5 : -0.5) * length * axis + radius * (std::cos(a) * u + std::sin(a) * w)));
            v.directions.emplace_back(glm::vec3(n));
            v.colors.push_back(color);
        }
        for (int s = 0; s < sides; ++s)
            v.indices.insert(v.indices.end(), {first, first + 1 + static_cast<std::uint32_t>(s), first + 1 + static_cast<std::uint32_t>((s + 1) % sides)});
    }
    return v;
}

void expectSameAmbientAndImage(const std::vector<std::uint16_t>& laoAmbient, const Image& laoImage,
                               const std::vector<std::uint16_t>& caoAmbient, const Image& caoImage, const std::string& what) {
    ASSERT_EQ(laoAmbient.size(), caoAmbient.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < laoAmbient.size(); ++i) differing += laoAmbient[i] != caoAmbient[i];
    EXPECT_EQ(differing, 0u) << what << ": V_AO differs in " << differing << " voxels";
    EXPECT_EQ(0, std::memcmp(laoImage.pixels.data(), caoImage.pixels.data(), laoImage.pixels.size() * sizeof(glm::vec4)))
        << what << ": images differ";
}

}  // namespace curette::test
