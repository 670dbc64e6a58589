// Contextual Ambient Occlusion: the exactness contract (CAO == full LAO, bit for bit, V_AO and image) over
// random poses, conservative dilation, the shader clip test against analytic shapes, the seam rule, rigid
// motion without map redraws, and defined behaviour on bad poses.
#include "base/error.h"
#include "clip/primitives.h"
#include "gl/bindings.h"
#include "render/reference/lao_reference.h"
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

namespace curette {
namespace {

using test::glContext;

double blobs(glm::dvec3 p) {
    const glm::dvec4 centres[] = {{-5, -3, 2, 6}, {6, 4, -3, 5}, {1, -7, -5, 4}, {0, 6, 6, 5}};
    double v = 0;
    for (const glm::dvec4& c : centres) v += 240.0 * std::exp(-glm::dot(p - glm::dvec3(c), p - glm::dvec3(c)) / (2 * c.w * c.w));
    return std::min(v, 255.0);
}

// A small scene: 28^3 voxels of 1 mm, LAO with K = 14, M = 7 (reach 6 mm), so a few hundred AO updates
// stay fast on llvmpipe.
struct CaoScene {
    VolumeData volume;
    TransferFunction tf;
    std::unique_ptr<Renderer> renderer;
    FrameDescription frame;
    explicit CaoScene(glm::ivec3 dims = glm::ivec3(28), LaoSettings::Dispatch dispatch = LaoSettings::Dispatch::Compacted) {
        glContext();
        volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, blobs);
        tf = test::rampTransferFunction(30, 180, 0.3);
        renderer = std::make_unique<Renderer>(glContext(), volume, tf);
        LaoSettings lao;
        parseLaoPattern("14", lao.directions);
        lao.samples = 7;
        lao.stepMm = 1.0;
        lao.antiAliasingSamples = 16;
        lao.dispatch = dispatch;
        renderer->setLaoSettings(lao);
        frame.camera.fit(glm::dvec3(0), 0.9 * glm::length(glm::dvec3(dims)) / 2);
        frame.camera.azimuthDeg = 30;
        frame.camera.elevationDeg = 20;
        frame.size = {48, 48};
    }
    struct Result {
        std::vector<std::uint16_t> ambient;
        Image image;
        std::uint64_t recomputed;
    };
    Result render(ShadingMode mode) {
        frame.shading = mode;
        renderer->render(frame);
        const AmbientOcclusion* ao = renderer->ambientOcclusion();
        return {ao->readAmbient(), renderer->readImage(), ao->lastStats().recomputed};
    }
};

clip::RigidPose randomPose(std::mt19937& random, double extent) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    clip::RigidPose pose;
    // Up to 30% beyond the volume's half-size: some poses are partly outside.
    pose.position = 0.65 * extent * glm::dvec3(u(random), u(random), u(random));
    glm::dvec3 axis = glm::normalize(glm::dvec3(u(random), u(random), u(random)) + glm::dvec3(1e-9));
    pose.orientation = glm::angleAxis(3.14159 * u(random), axis);
    return pose;
}

void expectBitIdentical(const CaoScene::Result& lao, const CaoScene::Result& cao, const std::string& what) {
    ASSERT_EQ(lao.ambient.size(), cao.ambient.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < lao.ambient.size(); ++i) differing += lao.ambient[i] != cao.ambient[i];
    EXPECT_EQ(differing, 0u) << what << ": V_AO differs in " << differing << " voxels";
    EXPECT_EQ(0, std::memcmp(lao.image.pixels.data(), cao.image.pixels.data(), lao.image.pixels.size() * sizeof(glm::vec4)))
        << what << ": images differ";
}

// The contract: over 50 random poses each of a sphere, a box and a torus (some partly outside the volume),
// and of two overlapping meshes, CAO gives V_AO and images bit-identical to recomputing LAO everywhere.
// The two step-V variants (compacted list, full grid) are both held to it.
TEST(Cao, EqualsFullLaoBitForBitOverRandomPoses) {
    for (auto dispatch : {LaoSettings::Dispatch::Compacted, LaoSettings::Dispatch::FullGrid}) {
        CaoScene scene(glm::ivec3(28), dispatch);
        std::mt19937 random(dispatch == LaoSettings::Dispatch::Compacted ? 1 : 2);
        struct Shape {
            const char* name;
            std::shared_ptr<const clip::TriangleMesh> mesh;
        };
        const Shape shapes[] = {{"sphere", std::make_shared<const clip::TriangleMesh>(clip::makeSphere(7.0, 3))},
                                {"box", std::make_shared<const clip::TriangleMesh>(clip::makeBox(glm::dvec3(12, 9, 7)))},
                                {"torus", std::make_shared<const clip::TriangleMesh>(clip::makeTorus(8.0, 3.0, 48, 24))}};
        int poses = dispatch == LaoSettings::Dispatch::Compacted ? 50 : 10;
        std::uint64_t recomputed = 0, total = 0;
        for (const Shape& shape : shapes) {
            clip::ClipMeshSet& set = scene.renderer->clipMeshes();
            set.clear();
            set.add(shape.mesh, glm::dvec3(1.0), {}, shape.name);
            for (int i = 0; i < poses; ++i) {
                set.setPose(0, randomPose(random, 28.0));
                CaoScene::Result lao = scene.render(ShadingMode::Lao);
                CaoScene::Result cao = scene.render(ShadingMode::Cao);
                expectBitIdentical(lao, cao, std::string(shape.name) + " pose " + std::to_string(i));
                recomputed += cao.recomputed;
                total += lao.recomputed;
                if (HasFailure()) return;
            }
        }
        // Two overlapping meshes (the union of clipped and of dilated regions, section 3.6).
        clip::ClipMeshSet& set = scene.renderer->clipMeshes();
        set.clear();
        set.add(shapes[0].mesh, glm::dvec3(1.0), {}, "sphere");
        set.add(shapes[1].mesh, glm::dvec3(1.0), {}, "box");
        for (int i = 0; i < poses; ++i) {
            clip::RigidPose a = randomPose(random, 28.0), b = a;
            b.position += glm::dvec3(5, -3, 2);
            b.orientation = randomPose(random, 1.0).orientation;
            set.setPose(0, a);
            set.setPose(1, b);
            expectBitIdentical(scene.render(ShadingMode::Lao), scene.render(ShadingMode::Cao), "two meshes pose " + std::to_string(i));
            if (HasFailure()) return;
        }
        std::printf("[ cao ] %s: CAO recomputed %.1f%% of what full LAO recomputed\n",
                    dispatch == LaoSettings::Dispatch::Compacted ? "compacted" : "full grid", 100.0 * static_cast<double>(recomputed) / static_cast<double>(total));
        EXPECT_LT(recomputed, total) << "CAO must skip voxels";
    }
}

// A CAO update visits only the box around this frame's and the last frame's meshes. Over a path a user could
// drive (small steps, jumps, leaving the volume and coming back, a second mesh added and removed), a renderer
// that only ever runs CAO must match one that recomputes full LAO every frame, bit for bit; and the box must
// really be smaller than the volume, or this test would not exercise it.
TEST(Cao, VisitingOnlyTheMeshRegionsStaysEqualToFullLao) {
    CaoScene caoOnly(glm::ivec3(64)), laoOnly(glm::ivec3(64));
    auto sphere = std::make_shared<const clip::TriangleMesh>(clip::makeSphere(4.0, 3));
    auto box = std::make_shared<const clip::TriangleMesh>(clip::makeBox(glm::dvec3(6, 5, 4)));
    for (CaoScene* s : {&caoOnly, &laoOnly}) s->renderer->clipMeshes().add(sphere, glm::dvec3(1.0), {}, "sphere");
    std::mt19937 random(21);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    clip::RigidPose pose;
    pose.position = {-10, 0, 0};
    int smallerThanTheVolume = 0;
    const int frames = 32;
    for (int frame = 0; frame < frames; ++frame) {
        if (frame == 10) pose.position = {12, 8, -6};      // a jump
        else if (frame == 15) pose.position = {80, 0, 0};  // out of the volume...
        else if (frame == 17) pose.position = {0, -8, 4};  // ...and back
        else pose.position += 1.5 * glm::dvec3(u(random), u(random), u(random));
        // Mostly upright (the box around a turned map box is larger), now and then turned.
        pose.orientation = frame % 6 == 3 ? randomPose(random, 1.0).orientation : glm::dquat(1.0, 0.0, 0.0, 0.0);
        for (CaoScene* s : {&caoOnly, &laoOnly}) {
            clip::ClipMeshSet& set = s->renderer->clipMeshes();
            if (frame == 20) set.add(box, glm::dvec3(1.0), {}, "box");
            if (frame == 27) set.remove(1);
            set.setPose(0, pose);
            if (set.count() > 1) set.setPose(1, {pose.position + glm::dvec3(-12, 5, 0), pose.orientation});
        }
        CaoScene::Result cao = caoOnly.render(ShadingMode::Cao);
        CaoScene::Result lao = laoOnly.render(ShadingMode::Lao);
        std::string what = "frame ";
        what += std::to_string(frame);
        expectBitIdentical(lao, cao, what);
        if (HasFailure()) return;
        const AmbientOcclusionStats& stats = caoOnly.renderer->ambientOcclusion()->lastStats();
        smallerThanTheVolume += stats.dispatched < stats.voxels / 2;
    }
    EXPECT_GT(smallerThanTheVolume, frames / 2) << "most CAO updates should visit less than half the volume";
}

// Dilation is conservative: every voxel whose LAO changes when the mesh moves lies in the dilated region.
// Full LAO (no dilation test) is the judge: a voxel CAO calls unaffected (category c) must have, under full
// LAO recompute, exactly its unclipped value, before and after the move.
TEST(Cao, NoVoxelOutsideTheDilatedRegionChangesItsAmbientOcclusion) {
    CaoScene scene;
    std::mt19937 random(9);
    clip::ClipMeshSet& set = scene.renderer->clipMeshes();
    set.add(std::make_shared<const clip::TriangleMesh>(clip::makeBox(glm::dvec3(10, 8, 14))), glm::dvec3(1.0), {}, "box");
    for (int i = 0; i < 20; ++i) {
        set.setPose(0, randomPose(random, 28.0));
        CaoScene::Result cao = scene.render(ShadingMode::Cao);
        std::vector<std::uint8_t> mask = scene.renderer->ambientOcclusion()->readMask();
        std::vector<std::uint16_t> precomputed = scene.renderer->ambientOcclusion()->readPrecomputed();
        CaoScene::Result lao = scene.render(ShadingMode::Lao);
        std::size_t unaffected = 0;
        for (std::size_t v = 0; v < mask.size(); ++v) {
            if (mask[v] != binding::categoryUnaffected) continue;
            ++unaffected;
            ASSERT_EQ(lao.ambient[v], precomputed[v]) << "voxel " << v << " changed outside the dilated region, pose " << i;
        }
        EXPECT_GT(unaffected, 0u);
    }
}

// The shader's clip test (nearest map pixel) agrees with the analytic inside test for every point farther
// than one voxel plus one map pixel from the surface; the dilated test holds every point within the
// dilation radius of the mesh; and step IV's "near any mesh" pre-test is conservative: every point either
// map test calls inside is near (and points far enough away are not, or the pre-test would skip nothing).
TEST(Cao, ShaderClipTestAgreesWithAnalyticSphereAndBox) {
    CaoScene scene;
    clip::ClipMeshSet& set = scene.renderer->clipMeshes();
    const double radius = 8.0;
    const glm::dvec3 half(6.0, 4.5, 7.5);
    std::mt19937 random(3);
    for (int shape = 0; shape < 2; ++shape) {
        set.clear();
        auto mesh = shape == 0 ? clip::makeSphere(radius, 5) : clip::makeBox(2.0 * half);
        clip::RigidPose pose = randomPose(random, 10.0);
        set.add(std::make_shared<const clip::TriangleMesh>(mesh), glm::dvec3(1.0), pose, shape == 0 ? "sphere" : "box");
        set.setDilationRadiusMm(5.0);
        set.setDilatedMapsNeeded(true);
        set.update();
        // Analytic signed distance in the mesh frame (negative inside), and the tessellation error of the
        // sphere (icosphere level 5: vertices on the sphere, flat faces at most 0.01 mm inside).
        glm::dmat4 toLocal = pose.inverseMatrix();
        auto signedDistance = [&](glm::dvec3 world) {
            glm::dvec3 q = glm::dvec3(toLocal * glm::dvec4(world, 1.0));
            if (shape == 0) return glm::length(q) - radius;
            glm::dvec3 d = glm::abs(q) - half;
            return glm::length(glm::max(d, 0.0)) + std::min(std::max({d.x, d.y, d.z}), 0.0);
        };
        std::vector<glm::vec4> points;
        std::uniform_real_distribution<double> u(-22.0, 22.0);
        for (int i = 0; i < 20000; ++i) points.emplace_back(glm::vec3(pose.position + glm::dvec3(u(random), u(random), u(random))), 0.0f);
        gl::Buffer in = gl::createBuffer(), out = gl::createBuffer();
        glNamedBufferStorage(in.name(), static_cast<GLsizeiptr>(points.size() * sizeof(glm::vec4)), points.data(), 0);
        glNamedBufferStorage(out.name(), static_cast<GLsizeiptr>(points.size() * 4), nullptr, GL_DYNAMIC_STORAGE_BIT);
        gl::Program probe = gl::Program::compute("clip_probe.comp");
        set.apply(probe);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, in.name());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, out.name());
        probe.set("clipMeshCount", 1);
        probe.set("pointCount", static_cast<unsigned>(points.size()));
        probe.dispatchCovering(glm::uvec3(static_cast<unsigned>(points.size()), 1, 1));
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::vector<std::uint32_t> results(points.size());
        glGetNamedBufferSubData(out.name(), 0, static_cast<GLsizeiptr>(results.size() * 4), results.data());
        double band = 1.0 + set.camera(0).pixelMm() * std::sqrt(2.0);
        int checked = 0, dilatedChecked = 0, far = 0;
        for (std::size_t i = 0; i < points.size(); ++i) {
            double d = signedDistance(glm::dvec3(points[i]));
            if (results[i] & 3u) {
                ASSERT_TRUE(results[i] & 4u) << "point " << i << " is inside a map but not near its box";
            }
            far += (results[i] & 4u) == 0;
            if (std::abs(d) > band) {
                ++checked;
                ASSERT_EQ((results[i] & 1u) != 0, d < 0) << (shape ? "box" : "sphere") << " point " << i << " at distance " << d;
            }
            if (d < 5.0) {
                ++dilatedChecked;
                ASSERT_TRUE(results[i] & 2u) << "point " << d << " mm from the surface is outside the dilated shape";
            }
        }
        EXPECT_GT(checked, 15000);
        EXPECT_GT(dilatedChecked, 1000);
        EXPECT_GT(far, 500) << "the near test must reject points well outside the map box";
        std::printf("[ clip probe ] %s: %d of %zu points far from the map box\n", shape ? "box" : "sphere", far, points.size());
    }
}

// The seam: voxels just inside the cut that trilinear sampling of V_AO reaches from a visible point hold
// their true LAO, not 1; voxels no visible point can reach hold 1.
TEST(Cao, VoxelsNextToTheCutHoldTheirTrueAmbientOcclusion) {
    CaoScene scene;
    clip::ClipMeshSet& set = scene.renderer->clipMeshes();
    set.add(std::make_shared<const clip::TriangleMesh>(clip::makeSphere(9.0, 3)), glm::dvec3(1.0), clip::RigidPose{glm::dvec3(3, -2, 1), {}}, "sphere");
    CaoScene::Result cao = scene.render(ShadingMode::Cao);
    const AmbientOcclusion* ao = scene.renderer->ambientOcclusion();
    std::vector<std::uint8_t> mask = ao->readMask();
    std::vector<std::uint16_t> opacity = ao->readOpacity();
    reference::Grid grid;
    grid.dims = scene.volume.dims;
    for (std::uint16_t o : opacity) grid.values.push_back(o / 65535.0);
    reference::LaoParameters p{scene.renderer->laoSettings().directions.build(), scene.renderer->laoSettings().samples,
                               scene.renderer->laoSettings().stepMm, scene.tf.unitLengthMm};
    const VolumeGeometry& g = scene.renderer->geometry();
    glm::ivec3 d = g.dims;
    int border = 0, deep = 0;
    for (int k = 0; k < d.z; ++k)
        for (int j = 0; j < d.y; ++j)
            for (int i = 0; i < d.x; ++i) {
                std::size_t v = scene.volume.linearIndex(i, j, k);
                if (mask[v] != binding::categoryClipped) continue;
                bool nextToVisible = false;
                for (int z = -1; z <= 1; ++z)
                    for (int y = -1; y <= 1; ++y)
                        for (int x = -1; x <= 1; ++x) {
                            glm::ivec3 n(i + x, j + y, k + z);
                            if (glm::any(glm::lessThan(n, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(n, d))) continue;
                            nextToVisible |= mask[scene.volume.linearIndex(n.x, n.y, n.z)] != binding::categoryClipped;
                        }
                if (nextToVisible) {
                    ++border;
                    double expected = reference::localAmbientOcclusion(grid, g.worldToTexture(), g.indexToWorld, {i, j, k}, p);
                    ASSERT_NEAR(cao.ambient[v] / 65535.0, expected, 2e-5) << "border voxel " << i << "," << j << "," << k;
                } else {
                    ++deep;
                    ASSERT_EQ(cao.ambient[v], 65535u);
                }
            }
    EXPECT_GT(border, 50);
    EXPECT_GT(deep, 50);
}

// Moving or rotating a mesh changes only its camera matrix; scaling it redraws its maps.
TEST(Cao, RigidMotionDoesNotRedrawMaps) {
    CaoScene scene;
    clip::ClipMeshSet& set = scene.renderer->clipMeshes();
    set.add(std::make_shared<const clip::TriangleMesh>(clip::makeSphere(6.0, 3)), glm::dvec3(1.0), {}, "sphere");
    scene.render(ShadingMode::Cao);
    std::uint64_t renders = set.mapRenderCount();
    std::mt19937 random(4);
    for (int i = 0; i < 5; ++i) {
        set.setPose(0, randomPose(random, 20.0));
        scene.render(ShadingMode::Cao);
        EXPECT_TRUE(scene.renderer->lastFrameUpdatedAmbient());
    }
    EXPECT_EQ(set.mapRenderCount(), renders);
    // A still scene costs step VI alone.
    scene.render(ShadingMode::Cao);
    EXPECT_FALSE(scene.renderer->lastFrameUpdatedAmbient());
    set.setScale(0, glm::dvec3(1.2));
    scene.render(ShadingMode::Cao);
    EXPECT_EQ(set.mapRenderCount(), renders + 1);
}

TEST(Cao, MeshFarOutsideLeavesThePrecomputedAmbientOcclusion) {
    CaoScene scene;
    clip::ClipMeshSet& set = scene.renderer->clipMeshes();
    set.add(std::make_shared<const clip::TriangleMesh>(clip::makeSphere(6.0, 3)), glm::dvec3(1.0), clip::RigidPose{glm::dvec3(500, 0, 0), {}}, "far");
    CaoScene::Result cao = scene.render(ShadingMode::Cao);
    EXPECT_EQ(cao.recomputed, 0u);
    EXPECT_EQ(cao.ambient, scene.renderer->ambientOcclusion()->readPrecomputed());
}

TEST(Cao, MeshLargerThanTheVolumeClipsEverything) {
    CaoScene scene;
    clip::ClipMeshSet& set = scene.renderer->clipMeshes();
    set.add(std::make_shared<const clip::TriangleMesh>(clip::makeSphere(100.0, 3)), glm::dvec3(1.0), {}, "huge");
    for (ShadingMode mode : {ShadingMode::Lao, ShadingMode::Cao}) {
        CaoScene::Result r = scene.render(mode);
        for (std::uint16_t a : r.ambient) ASSERT_EQ(a, 65535u);
        for (const glm::vec4& p : r.image.pixels) ASSERT_EQ(p.a, 0.0f);
    }
}

TEST(Cao, DegenerateScaleAndTooManyMeshesAreClearErrors) {
    CaoScene scene;
    clip::ClipMeshSet& set = scene.renderer->clipMeshes();
    auto sphere = std::make_shared<const clip::TriangleMesh>(clip::makeSphere(5.0, 2));
    try {
        set.add(sphere, glm::dvec3(1.0, 0.0, 1.0), {}, "flat");
        FAIL() << "a zero scale must be rejected";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "scale");
    }
    for (int i = 0; i < clip::ClipMeshSet::maxMeshes; ++i) set.add(sphere, glm::dvec3(1.0), {}, "m" + std::to_string(i));
    try {
        set.add(sphere, glm::dvec3(1.0), {}, "one too many");
        FAIL() << "the mesh limit must be enforced";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(std::to_string(clip::ClipMeshSet::maxMeshes)), std::string::npos);
    }
    // Sixteen meshes still render and CAO still equals LAO.
    std::mt19937 random(12);
    for (int i = 0; i < set.count(); ++i) set.setPose(i, randomPose(random, 28.0));
    expectBitIdentical(scene.render(ShadingMode::Lao), scene.render(ShadingMode::Cao), "16 meshes");
}

}  // namespace
}  // namespace curette
