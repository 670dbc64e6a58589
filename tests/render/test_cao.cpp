// Contextual Ambient Occlusion: the exactness contract (CAO == full LAO, bit for bit, V_AO and image) over
// random poses, conservative dilation, the shader clip test against analytic shapes, the seam rule, rigid
// motion without map redraws, and defined behaviour on bad poses.
#include "base/error.h"
#include "mesh/coverage.h"
#include "mesh/primitives.h"
#include "gl/bindings.h"
#include "render/label_overlay.h"
#include "render/mesh_voxel_box.h"
#include "render/reference/lao_reference.h"
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <optional>
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

// What a CAO test scene is made of: the volume (dims, affine, field), the TF and the LAO settings.
struct CaoSpec {
    glm::ivec3 dims{28};
    std::optional<glm::dmat4> affine{};   // unset: 1 mm voxels centred on the origin
    std::function<double(glm::dvec3)> field = blobs;
    TransferFunction tf = test::rampTransferFunction(30, 180, 0.3);
    const char* pattern = "14";
    int samples = 7;
    double stepMm = 1.0;
    LaoSettings::Dispatch dispatch = LaoSettings::Dispatch::Compacted;
};

// A small scene: 28^3 voxels of 1 mm, LAO with K = 14, M = 7 (reach 6 mm), so a few hundred AO updates
// stay fast on llvmpipe.
struct CaoScene {
    VolumeData volume;
    TransferFunction tf;
    std::unique_ptr<Renderer> renderer;
    FrameDescription frame;
    explicit CaoScene(glm::ivec3 dims = glm::ivec3(28), LaoSettings::Dispatch dispatch = LaoSettings::Dispatch::Compacted)
        : CaoScene(CaoSpec{.dims = dims, .dispatch = dispatch}) {}
    explicit CaoScene(const CaoSpec& spec) {
        glContext();
        volume = test::makeVolume(spec.dims, spec.affine ? *spec.affine : test::centredAffine(spec.dims), ScalarType::UInt8, spec.field);
        tf = spec.tf;
        renderer = std::make_unique<Renderer>(glContext(), volume, tf);
        LaoSettings lao;
        parseLaoPattern(spec.pattern, lao.directions);
        lao.samples = spec.samples;
        lao.stepMm = spec.stepMm;
        lao.antiAliasingSamples = 16;
        lao.dispatch = spec.dispatch;
        renderer->setLaoSettings(lao);
        const VolumeGeometry& g = renderer->geometry();
        if (spec.affine) frame.camera.fit(g.worldCenter(), 0.9 * g.boundingRadiusMm());
        else frame.camera.fit(glm::dvec3(0), 0.9 * glm::length(glm::dvec3(spec.dims)) / 2);
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
    test::expectSameAmbientAndImage(lao.ambient, lao.image, cao.ambient, cao.image, what);
}

std::size_t differingVoxels(const CaoScene::Result& lao, const CaoScene::Result& cao) {
    std::size_t differing = 0;
    for (std::size_t i = 0; i < lao.ambient.size() && i < cao.ambient.size(); ++i) differing += lao.ambient[i] != cao.ambient[i];
    return differing;
}

// Two renderers over the same volume, TF, LAO settings and meshes: `cao` only ever runs CAO (so voxels
// outside the box it visits hold what its own earlier updates wrote), `lao` is constructed fresh and only ever
// runs full LAO (every voxel recomputed, nothing carried over from CAO).
struct CaoAgainstFreshLao {
    CaoScene cao, lao;
    explicit CaoAgainstFreshLao(const CaoSpec& spec) : cao(spec), lao(spec) {}
    // Applies the same change to both renderers' meshes.
    template <typename F>
    void meshes(F&& change) {
        change(cao.renderer->clipMeshes());
        change(lao.renderer->clipMeshes());
    }
    struct Frame {
        CaoScene::Result lao, cao;
    };
    Frame render() {
        Frame f;
        f.cao = cao.render(ShadingMode::Cao);
        f.lao = lao.render(ShadingMode::Lao);
        return f;
    }
};

struct Shape {
    const char* name;
    std::shared_ptr<const clip::TriangleMesh> mesh;
};

struct PropertyCounts {
    std::uint64_t recomputed = 0, total = 0;   // voxels CAO recomputed, voxels full LAO recomputed
    int updates = 0, partial = 0;              // CAO updates, and those that visited less than the whole volume
    int leftStill = 0;                         // updates that left some of a still mesh's bricks unvisited
};

// Random poses of each shape, then of two overlapping meshes (the first two shapes), CAO against fresh
// full LAO, bit for bit.
PropertyCounts expectCaoEqualsFreshLaoOverRandomPoses(const CaoSpec& spec, const std::vector<Shape>& shapes, unsigned seed, int poses,
                                                      double extent, const std::string& label) {
    CaoAgainstFreshLao pair(spec);
    std::mt19937 random(seed);
    PropertyCounts counts;
    auto count = [&](const CaoAgainstFreshLao::Frame& f) {
        const AmbientOcclusionStats& stats = pair.cao.renderer->ambientOcclusion()->lastStats();
        counts.recomputed += f.cao.recomputed;
        counts.total += f.lao.recomputed;
        ++counts.updates;
        counts.partial += stats.dispatched < stats.voxels;
    };
    for (const Shape& shape : shapes) {
        pair.meshes([&](clip::ClipMeshSet& set) {
            set.clear();
            set.add(shape.mesh, glm::dvec3(1.0), {}, shape.name);
        });
        for (int i = 0; i < poses; ++i) {
            clip::RigidPose pose = randomPose(random, extent);
            pair.meshes([&](clip::ClipMeshSet& set) { set.setPose(0, pose); });
            CaoAgainstFreshLao::Frame f = pair.render();
            expectBitIdentical(f.lao, f.cao, label + ", " + shape.name + " pose " + std::to_string(i));
            count(f);
            if (::testing::Test::HasFailure()) return counts;
        }
    }
    // Two overlapping meshes (the union of clipped and of dilated regions, section 3.6).
    pair.meshes([&](clip::ClipMeshSet& set) {
        set.clear();
        set.add(shapes[0].mesh, glm::dvec3(1.0), {}, shapes[0].name);
        set.add(shapes[1].mesh, glm::dvec3(1.0), {}, shapes[1].name);
    });
    for (int i = 0; i < poses; ++i) {
        clip::RigidPose a = randomPose(random, extent), b = a;
        b.position += glm::dvec3(5, -3, 2);
        b.orientation = randomPose(random, 1.0).orientation;
        pair.meshes([&](clip::ClipMeshSet& set) {
            set.setPose(0, a);
            set.setPose(1, b);
        });
        CaoAgainstFreshLao::Frame f = pair.render();
        expectBitIdentical(f.lao, f.cao, label + ", two meshes pose " + std::to_string(i));
        count(f);
        if (::testing::Test::HasFailure()) return counts;
    }
    // One mesh moves and the other stays: an update leaves the still mesh's bricks alone, so the moving one
    // passes over it, near it and away from it, and comes back to where it was.
    clip::RigidPose still = randomPose(random, extent);
    pair.meshes([&](clip::ClipMeshSet& set) { set.setPose(1, still); });
    pair.render();
    const Renderer& cao = *pair.cao.renderer;
    for (int i = 0; i < poses; ++i) {
        clip::RigidPose a = randomPose(random, extent);
        if (i % 3 == 0) a.position = still.position + glm::dvec3(3, -2, 1);
        pair.meshes([&](clip::ClipMeshSet& set) { set.setPose(0, a); });
        CaoAgainstFreshLao::Frame f = pair.render();
        expectBitIdentical(f.lao, f.cao, label + ", one of two meshes moved, pose " + std::to_string(i));
        count(f);
        counts.leftStill += cao.ambientOcclusion()->lastStats().dispatched < bricksAroundMeshes(cao.geometry(), cao.clipMeshes()).visitedVoxels();
        if (::testing::Test::HasFailure()) break;
    }
    return counts;
}

std::vector<Shape> standardShapes(double size) {
    return {{"sphere", std::make_shared<const clip::TriangleMesh>(clip::makeSphere(7.0 * size, 3))},
            {"box", std::make_shared<const clip::TriangleMesh>(clip::makeBox(size * glm::dvec3(12, 9, 7)))},
            {"torus", std::make_shared<const clip::TriangleMesh>(clip::makeTorus(8.0 * size, 3.0 * size, 48, 24))}};
}

// The contract: over 50 random poses each of a sphere, a box and a torus (some partly outside the volume),
// and of two overlapping meshes, CAO gives V_AO and images bit-identical to recomputing LAO everywhere. The
// LAO side runs in a second, freshly constructed renderer that never runs CAO, and the CAO renderer never
// runs LAO: outside the box a CAO update visits, V_AO must already hold what full LAO writes because CAO's
// own earlier updates left it so. In the 28^3 scene every map box covers the volume; the 40^3 scene with a
// shorter reach and smaller meshes makes most updates visit a box inside it, so a CAO that forgets the last
// update's region (stale clipped voxels where the mesh was) fails here. The two step-V variants (compacted
// list, full grid) are both held to it.
TEST(Cao, EqualsFullLaoBitForBitOverRandomPoses) {
    struct Config {
        const char* name;
        CaoSpec spec;
        double shapeSize, extent;
        unsigned seed;
        int poses;
    };
    CaoSpec large{.dims = glm::ivec3(40), .samples = 4};
    CaoSpec largeFullGrid = large;
    largeFullGrid.dispatch = LaoSettings::Dispatch::FullGrid;
    const Config configs[] = {{"compacted", CaoSpec{}, 1.0, 28.0, 1, 50},
                              {"full grid", CaoSpec{.dispatch = LaoSettings::Dispatch::FullGrid}, 1.0, 28.0, 2, 10},
                              {"compacted, 40^3 reach 3 mm", large, 0.5, 40.0, 3, 20},
                              {"full grid, 40^3 reach 3 mm", largeFullGrid, 0.5, 40.0, 4, 8}};
    for (const Config& c : configs) {
        PropertyCounts counts = expectCaoEqualsFreshLaoOverRandomPoses(c.spec, standardShapes(c.shapeSize), c.seed, c.poses, c.extent, c.name);
        if (HasFailure()) return;
        std::printf("[ cao ] %s: CAO recomputed %.1f%% of what full LAO recomputed; %d of %d updates visited less than the volume\n",
                    c.name, 100.0 * static_cast<double>(counts.recomputed) / static_cast<double>(counts.total), counts.partial, counts.updates);
        EXPECT_LT(counts.recomputed, counts.total) << "CAO must skip voxels";
        EXPECT_GT(counts.leftStill, 0) << c.name << ": an update must leave a still mesh's bricks for the test to mean something";
        if (c.spec.dims.x == 40) {
            EXPECT_GT(counts.partial, counts.updates / 2) << c.name << ": most updates must visit a box inside the volume";
        }
    }
}

// The index-to-world affine of an anisotropic, oblique grid: spacing 0.6 x 0.9 x 2.5 mm, turned 20 degrees
// about an oblique axis, centred near (not on) the origin.
glm::dmat4 obliqueAffine(glm::ivec3 dims) {
    glm::dmat4 turn = glm::mat4_cast(glm::angleAxis(glm::radians(20.0), glm::normalize(glm::dvec3(1.0, 2.0, 3.0))));
    glm::dmat4 shift(1.0);
    shift[3] = glm::dvec4(0.7, -0.4, 0.3, 1.0);
    return shift * turn * test::centredAffine(dims, glm::dvec3(0.6, 0.9, 2.5));
}

// Blobs over a field with opacity everywhere in a 60 mm box, so clipping changes LAO wherever a mesh goes.
double waves(glm::dvec3 p) {
    return std::min(255.0, 110.0 + 80.0 * std::sin(0.45 * p.x) * std::sin(0.35 * p.y + 1.0) * std::sin(0.3 * p.z + 2.0) + 0.5 * blobs(p));
}

CaoSpec obliqueSpec(LaoSettings::Dispatch dispatch) {
    CaoSpec spec;
    spec.dims = glm::ivec3(40, 36, 24);   // 24 x 32 x 60 mm: map boxes (R = 9 mm) fit inside along the long axis
    spec.affine = obliqueAffine(spec.dims);
    spec.field = waves;
    spec.stepMm = 0.7;                    // different from every spacing and from the cell diagonal (2.72 mm)
    spec.samples = 6;                     // reach 3.5 mm
    spec.dispatch = dispatch;
    return spec;
}

// The contract on an anisotropic, oblique grid with an LAO step unlike any spacing: the dilation radius
// (cell diagonal of a sheared cell), the map box and the visited region are all derived from the affine, and
// CAO must still equal fresh full LAO bit for bit, over several seeds of random poses.
TEST(Cao, EqualsFreshLaoOnAnisotropicObliqueGrids) {
    for (auto dispatch : {LaoSettings::Dispatch::Compacted, LaoSettings::Dispatch::FullGrid}) {
        bool compacted = dispatch == LaoSettings::Dispatch::Compacted;
        std::uint64_t recomputed = 0, total = 0;
        int partial = 0, updates = 0;
        for (unsigned seed : compacted ? std::vector<unsigned>{31, 32, 33} : std::vector<unsigned>{34}) {
            PropertyCounts counts = expectCaoEqualsFreshLaoOverRandomPoses(
                obliqueSpec(dispatch), standardShapes(0.8), seed, 12, 40.0, std::string(compacted ? "compacted" : "full grid") + " seed " + std::to_string(seed));
            if (HasFailure()) return;
            recomputed += counts.recomputed;
            total += counts.total;
            partial += counts.partial;
            updates += counts.updates;
        }
        std::printf("[ cao ] oblique %s: CAO recomputed %.1f%% of what full LAO recomputed; %d of %d updates visited less than the volume\n",
                    compacted ? "compacted" : "full grid", 100.0 * static_cast<double>(recomputed) / static_cast<double>(total), partial, updates);
        EXPECT_LT(recomputed, total) << "CAO must skip voxels";
        EXPECT_GT(partial, updates / 8) << "updates must also visit boxes inside the volume";
    }
}

// Turned meshes: a rod (its map box long along the rod) turned towards the grid's diagonals, whose
// axis-aligned bounds hold several times the voxels of its oriented map box, and for part of the path a
// turned box beside it. A CAO update visits only the bricks the oriented map boxes reach, now or at the last
// update (render/mesh_voxel_box.h); along a path of small steps, wobbles and a jump, CAO must equal fresh full
// LAO bit for bit on every frame, while visiting well under what the axis-aligned boxes of both frames held.
// Opacity everywhere (waves), so a voxel left out that needed its LAO recomputed or reset shows.
TEST(Cao, TurnedMeshesVisitOnlyTheirOrientedBoxesAndStayEqualToFullLao) {
    CaoSpec spec{.dims = glm::ivec3(48), .field = waves, .samples = 4};   // reach 3 mm, R = 6.5 mm
    CaoAgainstFreshLao pair(spec);
    const VolumeGeometry& g = pair.cao.renderer->geometry();
    auto rod = std::make_shared<const clip::TriangleMesh>(clip::makeCylinder(2.5, 30.0, 24));
    auto boxMesh = std::make_shared<const clip::TriangleMesh>(clip::makeBox(glm::dvec3(4.0, 5.0, 12.0)));
    pair.meshes([&](clip::ClipMeshSet& set) { set.add(rod, glm::dvec3(1.0), {}, "rod"); });
    auto turnFromZ = [](glm::dvec3 to) {   // the turn taking local +z (the rod's axis, its map box's depth) to `to`
        glm::dvec3 from(0, 0, 1);
        to = glm::normalize(to);
        return glm::angleAxis(std::acos(glm::dot(from, to)), glm::normalize(glm::cross(from, to)));
    };
    const glm::dquat diagonal = turnFromZ({1, 1, 1}), otherDiagonal = turnFromZ({-1, 1, 1});
    std::mt19937 random(17);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    glm::dvec3 position(-4, 2, 1);
    std::optional<plan::VoxelBox> lastBox;
    std::uint64_t visited = 0, axisAligned = 0;
    int partial = 0;
    const int frames = 24;
    for (int frame = 0; frame < frames; ++frame) {
        position = frame == 12 ? glm::dvec3(6, -5, 3) : position + 1.2 * glm::dvec3(u(random), u(random), u(random));
        glm::dquat wobble = glm::angleAxis(0.15 * u(random), glm::normalize(glm::dvec3(u(random), u(random), u(random)) + glm::dvec3(1e-9)));
        clip::RigidPose pose{position, wobble * (frame < 16 ? diagonal : otherDiagonal)};
        pair.meshes([&](clip::ClipMeshSet& set) {
            if (frame == 6) set.add(boxMesh, glm::dvec3(1.0), {}, "box");
            if (frame == 18) set.remove(1);
            set.setPose(0, pose);
            if (set.count() > 1) set.setPose(1, {position + glm::dvec3(-7, 6, -3), wobble * otherDiagonal});
        });
        CaoAgainstFreshLao::Frame f = pair.render();
        expectBitIdentical(f.lao, f.cao, "turned meshes, frame " + std::to_string(frame));
        if (HasFailure()) return;
        // What visiting the axis-aligned box around both frames' map boxes (before bricks) would have visited.
        plan::VoxelBox box = voxelBoxAroundMeshes(g, pair.cao.renderer->clipMeshes());
        plan::VoxelBox both = box;
        if (lastBox) {
            glm::ivec3 first = glm::min(box.origin, lastBox->origin), end = glm::max(box.origin + box.size, lastBox->origin + lastBox->size);
            both = {first, end - first};
        }
        lastBox = box;
        const AmbientOcclusionStats& stats = pair.cao.renderer->ambientOcclusion()->lastStats();
        if (frame == 0) continue;   // the first update after step I visits every voxel
        visited += stats.dispatched;
        axisAligned += both.voxelCount();
        partial += stats.dispatched < stats.voxels;
    }
    std::printf("[ cao turned ] CAO visited %.1f%% of the voxels the axis-aligned boxes held; %d of %d updates partial\n",
                100.0 * double(visited) / double(axisAligned), partial, frames - 1);
    EXPECT_EQ(partial, frames - 1);
    EXPECT_LT(visited, axisAligned / 2) << "the oriented boxes' bricks must hold well under the axis-aligned boxes";
}

// A scene where the dilation radius R = reach + (1 + h) cell diagonals and the kernel's sqrt(2) map pixels are
// both needed, not just safe. Every term of the derivation (render/passes/ambient_occlusion.cpp, render/passes/clip_mesh_set.cpp
// kernelRadiusMm) is made to reach its bound along one line:
//  - a 1 mm grid turned so its cell diagonal (1, 1, 1) points along world +x, and one LAO direction
//    (Fibonacci K = 1: world +x, no jitter), M = 2, step 1.1 cell diagonals: the only LAO sample q of voxel v
//    lies at v + 1.1 (1, 1, 1) (index), and its trilinear footprint reaches the corner u = v + (2, 2, 2);
//  - only the lattice plane of u is opaque (alpha 1 per mm), so V_AO(v) = (1 + (1 - V_o(u) f^3)^e) / 2 with
//    f = 0.1: it changes (by ~2.5 R16 steps) when V_o(u) drops by one clip sample of 25;
//  - a box whose -x face lies just before s = u + h (1, 1, 1), u's corner clip sample (h =
//    clip::kCellSampleHalfWidth): s is clipped, v is |s - v| = (2 + h) cell diagonals = 4.305 mm from it,
//    R = 4.478 mm;
//  - the face is parallel to the box's clipping camera axis, so the map pixels quantise the distance: a
//    kernel covers v only if floor(kernel / px) px >= 5.196 mm when s sits just past a pixel edge.
// Box sizes (map pixel 0.39-0.48 mm) and offsets along x (one lattice step) are scanned. The correct radius
// must give CAO == fresh LAO everywhere; a radius one cell diagonal short, or a kernel without the sqrt(2)
// pixel term (injected: the radius is set so kernelRadiusMm equals R + epsilon; the renderer sets the
// radius only at construction and in setLaoSettings, so it stays), must break it somewhere (the test prints
// in how many configurations each does).
constexpr double kSqrt3 = 1.7320508075688772;

glm::dmat4 cellDiagonalAlongX(glm::ivec3 dims) {
    glm::dvec3 from = glm::normalize(glm::dvec3(1.0)), to(1.0, 0.0, 0.0);
    glm::dquat turn = glm::angleAxis(std::acos(glm::dot(from, to)), glm::normalize(glm::cross(from, to)));
    return glm::mat4_cast(turn) * test::centredAffine(dims);
}

// World x of lattice plane i + j + k = level of cellDiagonalAlongX(24^3) (planes 1/sqrt(3) mm apart).
double latticePlaneX(double level) { return (level - 3 * 11.5) / kSqrt3; }

CaoSpec tightSpec() {
    CaoSpec spec;
    spec.dims = glm::ivec3(24);
    spec.affine = cellDiagonalAlongX(spec.dims);
    const double opaqueX = latticePlaneX(30);   // the plane of the voxels u
    spec.field = [opaqueX](glm::dvec3 p) { return std::abs(p.x - opaqueX) < 0.2 ? 255.0 : 0.0; };
    spec.tf.color = {{0, glm::dvec3(0.8)}};
    spec.tf.opacity = {{0, 0.0}, {254, 0.0}, {255, 1.0}};
    spec.pattern = "fib1";
    spec.samples = 2;
    spec.stepMm = 1.1 * kSqrt3;
    return spec;
}

TEST(Cao, DilationRadiusIsTightEnoughToMatter) {
    const double clippedPlaneX = latticePlaneX(30 + 3 * clip::kCellSampleHalfWidth);   // the corner samples s = u + h (1, 1, 1)
    enum Variant { Correct, OneCellDiagonalShort, NoPixelTerm };
    const char* names[] = {"correct radius", "radius one cell diagonal short", "kernel without the sqrt(2) pixel term"};
    int failing[3] = {0, 0, 0}, configurations = 0;
    for (Variant variant : {Correct, OneCellDiagonalShort, NoPixelTerm}) {
        configurations = 0;
        for (double side = 15.0; side <= 21.01; side += 0.5) {
            CaoAgainstFreshLao pair(tightSpec());
            const VolumeGeometry& g = pair.cao.renderer->geometry();
            const double R = AmbientOcclusion::dilationRadiusMm(pair.cao.renderer->laoSettings(), g);
            // The scene needs R >= 2 + h cell diagonals (the chain v -> s); R = 2.1 + h of them today.
            if (side == 15.0 && variant == Correct) std::printf("[ cao tight ] R %.4f mm, |s - v| %.4f mm\n", R, (2 + clip::kCellSampleHalfWidth) * kSqrt3);
            auto box = std::make_shared<const clip::TriangleMesh>(clip::makeBox(glm::dvec3(8.0, side, 12.0)));
            pair.meshes([&](clip::ClipMeshSet& set) { set.add(box, glm::dvec3(1.0), clip::RigidPose{glm::dvec3(clippedPlaneX + 4.0, 0, 0), {}}, "box"); });
            clip::ClipMeshSet& caoSet = pair.cao.renderer->clipMeshes();
            double radius = R;
            if (variant == OneCellDiagonalShort) radius = R - g.cellDiagonalMm();
            if (variant == NoPixelTerm) {
                // The radius whose kernel is what kernelRadiusMm(R) would be without sqrt(2) px (the pixel size
                // depends on the radius through the map margin: a few fixed-point steps).
                const double target = R + 1e-3 * R + 1e-3;
                for (int step = 0; step < 6; ++step) {
                    caoSet.setDilationRadiusMm(radius);
                    caoSet.update();
                    radius += target - caoSet.kernelRadiusMm(0);
                }
            }
            pair.meshes([&](clip::ClipMeshSet& set) { set.setDilationRadiusMm(radius); });
            caoSet.update();
            for (double shift = 0.0; shift < 0.59; shift += 0.04, ++configurations) {
                clip::RigidPose pose{glm::dvec3(clippedPlaneX + 4.0 - shift, 0.3, -0.2), {}};
                pair.meshes([&](clip::ClipMeshSet& set) { set.setPose(0, pose); });
                CaoAgainstFreshLao::Frame f = pair.render();
                std::size_t differing = differingVoxels(f.lao, f.cao);
                failing[variant] += differing > 0;
                if (variant == Correct) {
                    expectBitIdentical(f.lao, f.cao, "box side " + std::to_string(side) + " shift " + std::to_string(shift));
                    if (HasFailure()) return;
                }
            }
        }
        std::printf("[ cao tight ] %s: CAO != fresh LAO in %d of %d configurations\n", names[variant], failing[variant], configurations);
    }
    EXPECT_EQ(failing[Correct], 0);
    EXPECT_GT(failing[OneCellDiagonalShort], 0) << "shrinking R by a cell diagonal must break CAO == LAO in this scene";
    EXPECT_GT(failing[NoPixelTerm], 0) << "dropping the sqrt(2) pixel term must break CAO == LAO in this scene";
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
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboProbePoints, in.name());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboProbeResults, out.name());
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

// Step IV tests a voxel's clip samples only against the meshes whose depth box lies within their reach
// (clip_test.glsl nearDepthBox), the ray caster only the stretch of each ray that meets one: V_o, V_m, V_AO
// and the image are those of testing every sample against every mesh, bit for bit, in cao (the dilated
// meshes) and lao (every mesh near the voxel), with three meshes that overlap, one of them turned and one a
// torus with two intervals.
TEST(Cao, DepthBoxTestsChangeNoVoxelAndNoPixel) {
    auto mesh = [](clip::TriangleMesh m) { return std::make_shared<const clip::TriangleMesh>(std::move(m)); };
    auto addMeshes = [&](CaoScene& scene) {
        clip::ClipMeshSet& set = scene.renderer->clipMeshes();
        set.add(mesh(clip::makeSphere(6.5, 3)), glm::dvec3(1.0), clip::RigidPose{glm::dvec3(3.3, -2.1, 1.7), {}}, "sphere");
        set.add(mesh(clip::makeBox({7, 5, 9})), glm::dvec3(1.0),
                clip::RigidPose{glm::dvec3(-2.4, 3.1, -1.2), glm::angleAxis(glm::radians(33.0), glm::normalize(glm::dvec3(1, 2, 0.5)))}, "turned box");
        set.add(mesh(clip::makeTorus(6, 2, 48, 16)), glm::dvec3(1.0),
                clip::RigidPose{glm::dvec3(1.1, 1.9, -4.3), glm::angleAxis(glm::radians(67.0), glm::normalize(glm::dvec3(0.3, -1, 1)))}, "torus");
    };
    for (ShadingMode mode : {ShadingMode::Cao, ShadingMode::Lao}) {
        SCOPED_TRACE(shadingModeName(mode));
        CaoScene every, near;
        addMeshes(every);
        addMeshes(near);
        every.renderer->clipMeshes().setDepthBoxTests(false);
        CaoScene::Result a = every.render(mode), b = near.render(mode);
        const AmbientOcclusion& aoA = *every.renderer->ambientOcclusion();
        const AmbientOcclusion& aoB = *near.renderer->ambientOcclusion();
        std::vector<std::uint16_t> opacity = aoA.readOpacity();
        EXPECT_EQ(opacity, aoB.readOpacity()) << "V_o";
        EXPECT_EQ(aoA.readMask(), aoB.readMask()) << "V_m";
        EXPECT_EQ(a.ambient, b.ambient) << "V_AO";
        EXPECT_EQ(0, std::memcmp(a.image.pixels.data(), b.image.pixels.data(), a.image.pixels.size() * sizeof(glm::vec4))) << "image";
        // The carve is there: some voxels are partly clipped (their samples disagree).
        std::vector<std::uint16_t> unclipped;
        {
            CaoScene plain;
            plain.render(mode);
            unclipped = plain.renderer->ambientOcclusion()->readOpacity();
        }
        int partly = 0;
        for (std::size_t v = 0; v < opacity.size(); ++v) partly += opacity[v] != 0 && opacity[v] < unclipped[v];
        EXPECT_GT(partly, 200) << "the meshes must cut through tissue for the test to mean something";
    }
}

// Steps I and V cast no LAO ray from a voxel no visible sample reads (LaoSettings::onlyWhereSeen,
// lao_common.glsl ambientSeen): such voxels hold 1, every other voxel its LAO, and no pixel changes, in cao
// and lao, from several sides, with a mesh carving the tissue. Two volumes of 40^3: blobs under a ramp TF
// (empty bricks around them), and the hard case, a ball whose values fall from 230 to 0 within 1.5 voxels
// under a TF that is opaque only around 110: a shell of tissue one or two voxels thick, samples interpolated
// across the fall, and bricks inside the ball as empty as those outside; and that ball with a shown label on
// a cube of its transparent inside (a label raises opacity where the TF gives none). Taking a voxel's
// neighbour's brick instead of its own changes pixels.
TEST(Cao, LaoOnlyWhereASampleSeesItChangesNoPixel) {
    CaoSpec blobsSpec;
    blobsSpec.dims = glm::ivec3(40);
    CaoSpec ballSpec = blobsSpec;
    ballSpec.field = [](glm::dvec3 p) {
        return 230.0 * std::clamp((11.3 - glm::length(p - glm::dvec3(3.0, -2.0, 1.0))) / 1.5 + 0.5, 0.0, 1.0);
    };
    ballSpec.tf.opacity = {{0.0, 0.0}, {90.0, 0.0}, {110.0, 0.8}, {130.0, 0.0}, {255.0, 0.0}};
  struct Case {
    const char* name;
    CaoSpec spec;
    bool labelled;   // a shown label on a cube of the ball's transparent inside, which the sphere opens
  };
  for (const Case& c : {Case{"blobs", blobsSpec, false}, Case{"ball", ballSpec, false}, Case{"ball with a label", ballSpec, true}}) {
    SCOPED_TRACE(c.name);
    const CaoSpec& spec = c.spec;
    auto carve = [](CaoScene& scene) {
        scene.renderer->clipMeshes().add(std::make_shared<const clip::TriangleMesh>(clip::makeSphere(6.0, 3)), glm::dvec3(1.0),
                                         clip::RigidPose{glm::dvec3(4.5, -2.0, 6.5), {}}, "sphere");
        scene.frame.size = {64, 64};
    };
    CaoScene seen(spec), every(spec);
    if (c.labelled) {
        std::vector<std::uint16_t> ids(std::size_t(spec.dims.x) * spec.dims.y * spec.dims.z, 0);
        for (int k = 17; k <= 24; ++k)
            for (int j = 14; j <= 21; ++j)
                for (int i = 19; i <= 26; ++i) ids[(std::size_t(k) * spec.dims.y + j) * spec.dims.x + i] = 1;
        std::vector<glm::vec4> styles{glm::vec4(0.0f), glm::vec4(0.9f, 0.2f, 0.2f, 0.5f)};
        for (CaoScene* scene : {&seen, &every}) scene->renderer->setLabels(std::make_unique<LabelOverlay>(spec.dims, ids, styles));
    }
    LaoSettings all = every.renderer->laoSettings();
    all.onlyWhereSeen = false;
    every.renderer->setLaoSettings(all);
    carve(seen);
    carve(every);
    for (ShadingMode mode : {ShadingMode::Cao, ShadingMode::Lao}) {
        SCOPED_TRACE(shadingModeName(mode));
        for (double azimuth : {30.0, 150.0, 260.0}) {
            SCOPED_TRACE(azimuth);
            seen.frame.camera.azimuthDeg = every.frame.camera.azimuthDeg = azimuth;
            CaoScene::Result a = seen.render(mode), b = every.render(mode);
            ASSERT_EQ(a.ambient.size(), b.ambient.size());
            std::size_t unseen = 0, differing = 0;
            for (std::size_t v = 0; v < a.ambient.size(); ++v) {
                if (a.ambient[v] == b.ambient[v]) continue;
                if (a.ambient[v] == 65535) ++unseen;
                else ++differing;
            }
            EXPECT_EQ(differing, 0u) << "a voxel the rule computes differs from its LAO";
            // Voxels whose LAO is below 1 but which hold 1: were a pixel to read one, it would change.
            EXPECT_GT(unseen, 200u);
            EXPECT_LT(a.recomputed, b.recomputed);
            if (mode == ShadingMode::Lao) {
                EXPECT_GT(b.recomputed - a.recomputed, a.ambient.size() / 5) << "rays saved";
            }
            EXPECT_EQ(0, std::memcmp(a.image.pixels.data(), b.image.pixels.data(), a.image.pixels.size() * sizeof(glm::vec4))) << "image";
        }
    }
  }
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

// The clip maps depend on the meshes alone, not on what the set held before: a set whose arrays were allocated
// for a larger mesh draws the maps (and so V_AO and the image) a fresh set draws. A saved scene so renders what
// the viewer showed. Scales 1.4 -> 1.0 of a 12 mm sphere: the wanted resolution (72 -> 92 pixels at 0.5 mm)
// shrinks by less than half, so the arrays stay at the larger size.
TEST(Cao, TheClipMapsDependOnTheMeshesNotOnWhatTheSetHeldBefore) {
    auto sphere = std::make_shared<const clip::TriangleMesh>(clip::makeSphere(12.0, 3));
    clip::RigidPose pose{glm::dvec3(7.0, 6.0, 5.0), {}};
    CaoScene used, fresh;
    used.renderer->clipMeshes().add(sphere, glm::dvec3(1.4), pose, "sphere");
    used.render(ShadingMode::Cao);
    int larger = used.renderer->clipMeshes().resolution();
    used.renderer->clipMeshes().setScale(0, glm::dvec3(1.0));
    CaoScene::Result a = used.render(ShadingMode::Cao);
    fresh.renderer->clipMeshes().add(sphere, glm::dvec3(1.0), pose, "sphere");
    CaoScene::Result b = fresh.render(ShadingMode::Cao);
    const clip::ClipMeshSet& u = used.renderer->clipMeshes();
    const clip::ClipMeshSet& f = fresh.renderer->clipMeshes();
    ASSERT_LT(f.resolution(), larger) << "the smaller mesh must want fewer pixels for the test to mean something";
    EXPECT_GT(u.allocatedResolution(), f.allocatedResolution()) << "the used set keeps its larger arrays";
    EXPECT_EQ(u.resolution(), f.resolution());
    for (int layer = 0; layer < 2; ++layer)
        for (bool dilated : {false, true}) EXPECT_EQ(u.readMap(0, layer, dilated), f.readMap(0, layer, dilated)) << "layer " << layer << (dilated ? " dilated" : "");
    EXPECT_EQ(a.ambient, b.ambient);
    EXPECT_EQ(a.image.pixels.size(), b.image.pixels.size());
    EXPECT_TRUE(a.image.pixels == b.image.pixels) << "the image depends on the set's history";
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
    for (int i = 0; i < clip::ClipMeshSet::maxMeshes; ++i) {
        std::string name = "m";
        name += std::to_string(i);
        set.add(sphere, glm::dvec3(1.0), {}, name);
    }
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
