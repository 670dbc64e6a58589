#pragma once
// The scene of the preview and exact-frame tests (test_preview.cpp, test_exact_in_slices.cpp): a 45 x 39 x 42
// grid (partial bricks on every upper face) of 1 mm voxels, LAO K = 14, M = 4, and a 5 mm sphere on a path
// across the blobs, 5 mm a pose. The bricks its dilated box reaches (a box of about 25 mm) at poses far apart
// differ, so an update that forgot where the mesh was would leave voxels behind. 48 x 40 pixels: 5 rows of
// 8 x 8 tiles.
#include "mesh/primitives.h"
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"

#include <cstring>
#include <memory>

namespace curette::test {

struct MovingSphereScene {
    VolumeData volume;
    TransferFunction tf = rampTransferFunction(30, 180, 0.3);
    std::unique_ptr<Renderer> renderer;
    FrameDescription frame;
    std::shared_ptr<const clip::TriangleMesh> sphere = std::make_shared<const clip::TriangleMesh>(clip::makeSphere(5.0, 3));
    explicit MovingSphereScene(ShadingMode mode = ShadingMode::Cao) {
        glContext();
        glm::ivec3 dims(45, 39, 42);
        volume = makeVolume(dims, centredAffine(dims), ScalarType::UInt8, blobField);
        renderer = std::make_unique<Renderer>(glContext(), volume, tf);
        renderer->setLaoSettings(lightLao(4));
        renderer->clipMeshes().add(sphere, glm::dvec3(1.0), pose(0), "sphere");
        frame.camera.fit(glm::dvec3(0), 0.9 * glm::length(glm::dvec3(dims)) / 2);
        frame.camera.azimuthDeg = 30;
        frame.camera.elevationDeg = 20;
        frame.size = {48, 40};
        frame.shading = mode;
    }
    // Pose n of the path across the blobs.
    static clip::RigidPose pose(int n) {
        clip::RigidPose p;
        p.position = glm::dvec3(-10.0 + 5.0 * n, 6.0 - 3.0 * n, 2.0);
        return p;
    }
    void moveTo(int n) { renderer->clipMeshes().setPose(0, pose(n)); }
    std::vector<std::uint16_t> ambient() const { return renderer->ambientOcclusion()->readAmbient(); }
};

// Two images equal bit for bit.
inline bool sameImage(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec4)) == 0;
}

}  // namespace curette::test
