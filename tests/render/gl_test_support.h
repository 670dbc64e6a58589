#pragma once
// Shared pieces of the GL tests: one headless context per test process, and small synthetic volumes
// written from analytic functions (so tests know the answer).

#include "gl/context.h"
#include "base/transfer_function.h"
#include "base/volume.h"
#include "render/model/frame.h"
#include "render/model/image.h"
#include "render/model/lao_settings.h"
#include "render/model/tube_vertices.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace curette {
class Renderer;
}

namespace curette::test {

// The process-wide headless EGL context (created on first use, current on return).
gl::Context& glContext();

// A volume whose voxel (i,j,k) holds f(world position of its centre). Stored as `type` (UInt8 values are
// rounded and clamped to 0..255; Float32 exact).
VolumeData makeVolume(glm::ivec3 dims, const glm::dmat4& indexToWorld, ScalarType type,
                      const std::function<double(glm::dvec3)>& f);

// A frame of the orbit camera around `target` (fov 30 degrees, near 1 mm, far 1000 mm unless changed after).
FrameDescription frameLookingAt(glm::dvec3 target, double distanceMm, double azimuthDeg, double elevationDeg, glm::ivec2 size,
                                ShadingMode shading);

// An axis-aligned volume of `dims` 1 mm voxels centred on the world origin.
glm::dmat4 centredAffine(glm::ivec3 dims, glm::dvec3 spacing = glm::dvec3(1.0));

// A smooth field of four Gaussian blobs in a 40 mm box around the origin, values 0..255.
double blobField(glm::dvec3 p);

// LAO light enough for small test volumes: K = 14 directions, M = `samples` steps of 1 mm, 16 anti-aliasing samples.
LaoSettings lightLao(int samples);

// A frame's V_AO (empty in a mode without ambient occlusion) and image, rendered whole.
struct AmbientAndImage {
    std::vector<std::uint16_t> ambient;
    Image image;
};
AmbientAndImage renderAmbientAndImage(Renderer& renderer, const FrameDescription& frame);

// The CAO contract's check: V_AO and the image of full LAO and of CAO equal bit for bit (gtest expectations
// naming `what`).
void expectSameAmbientAndImage(const std::vector<std::uint16_t>& laoAmbient, const Image& laoImage,
                               const std::vector<std::uint16_t>& caoAmbient, const Image& caoImage, const std::string& what);

// A simple TF over [0, 255]: grey ramp colour, opacity ramp from `lo` (0) to `hi` (alpha).
TransferFunction rampTransferFunction(double lo, double hi, double alpha);

// A straight capped tube along `axis` through `centre`, built directly (the tract pipeline has its own
// tests); enough for occlusion tests.
TubeVertices straightTube(glm::dvec3 centre, glm::dvec3 axis, double length, double radius, glm::vec4 color);

}  // namespace curette::test
