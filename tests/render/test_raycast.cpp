// Ray casting (shaders/raycast.comp) against its CPU double twin and against analytic answers.
#include "render/reference/raycast_reference.h"
#include "mesh/primitives.h"
#include "render/renderer.h"
#include "render/transfer_function_texture.h"
#include "tests/render/gl_test_support.h"

#include "base/error.h"

#include <gtest/gtest.h>

#include <tuple>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <random>
#include <utility>

namespace curette {
namespace {

using test::glContext;

using test::frameLookingAt;

// The blobby field of the GL tests (gl_test_support.h).
double blobs(glm::dvec3 p) { return test::blobField(p); }

TransferFunction blobTransferFunction() {
    TransferFunction tf;
    tf.color = {{0, {0.1, 0.2, 0.6}}, {80, {0.9, 0.4, 0.2}}, {160, {1.0, 0.9, 0.7}}, {255, {1, 1, 1}}};
    tf.opacity = {{0, 0}, {40, 0}, {120, 0.15}, {200, 0.5}, {255, 0.6}};
    tf.material = {0.25, 0.7, 0.4, 24.0};
    return tf;
}

struct Comparison {
    double maxError = 0, rmsError = 0;
    int pixels = 0, nonEmpty = 0;
    Image image;  // the GPU image the pixels were taken from
};

Comparison compareWithReference(const VolumeData& volume, const TransferFunction& tf, const FrameDescription& frame,
                                int pixelCount, unsigned seed) {
    Renderer renderer(glContext(), volume, tf);
    renderer.render(frame);
    Image image = renderer.readImage();
    double step = renderer.resolveStepMm(frame.raycast);
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> x(0, frame.size.x - 1), y(0, frame.size.y - 1);
    Comparison c;
    double sum = 0;
    for (int n = 0; n < pixelCount; ++n) {
        glm::ivec2 p(x(random), y(random));
        glm::dvec4 expected = reference::raycastPixel(volume, tf, frame, step, p).rgba;
        glm::dvec4 got(image.at(p.x, p.y));
        for (int ch = 0; ch < 4; ++ch) {
            double e = std::abs(got[ch] - expected[ch]);
            c.maxError = std::max(c.maxError, e);
            sum += e * e;
        }
        c.nonEmpty += expected.a > 0.01;
        ++c.pixels;
    }
    c.rmsError = std::sqrt(sum / (4.0 * c.pixels));
    std::printf("[ reference ] %s: max %.2e rms %.2e over %d pixels (%d non-empty)\n", shadingModeName(frame.shading),
                c.maxError, c.rmsError, c.pixels, c.nonEmpty);
    c.image = std::move(image);
    return c;
}

// Float32 storage isolates the ray caster's arithmetic from texture quantisation. What remains: float vs
// double arithmetic along ~300 samples, and the 4096-texel baked TF (linear between texels, so a kink of
// the piecewise-linear TF is rounded over one texel: |error| <= slope change * 255/4095 / 4 ~ 1e-4 in
// opacity per unit length). Measured: max 6e-5. Bound: 5e-4 per channel.
TEST(Raycast, MatchesCpuReferenceFloatVolumeSolidAndPhong) {
    glContext();
    glm::ivec3 dims(40);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::Float32, blobs);
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong}) {
        FrameDescription frame = frameLookingAt(glm::dvec3(0), 90, 30, 20, {96, 96}, mode);
        Comparison c = compareWithReference(volume, blobTransferFunction(), frame, 300, 7);
        EXPECT_GT(c.nonEmpty, 100) << "the test must look at the object";
        EXPECT_LT(c.maxError, 5e-4) << shadingModeName(mode) << " rms " << c.rmsError;
        RecordProperty(std::string("max_error_") + shadingModeName(mode), std::to_string(c.maxError));
    }
}

// A lattice step of 1, 1/2 or 1/4 of the TF's unit length takes 0, 1 or 2 square roots instead of pow
// (transfer_function.glsl, correctStepOpacity), any other step pow: each matches the reference as pow did.
TEST(Raycast, StepOpacityByRootsOrPowMatchesCpuReference) {
    glContext();
    glm::ivec3 dims(40);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::Float32, blobs);
    TransferFunction tf = blobTransferFunction();
    tf.unitLengthMm = 2.0;
    TransferFunctionTexture table(tf, 1.0, 0.0);
    const std::vector<std::pair<double, const char*>> steps = {{2.0, "0"}, {1.0, "1"}, {0.5, "2"}, {0.6, nullptr}};
    for (auto [stepMm, roots] : steps) {
        gl::Defines defines;
        table.addStepDefines(defines, stepMm);
        if (roots) EXPECT_EQ(defines, (gl::Defines{{"STEP_OPACITY_ROOTS", roots}})) << stepMm << " mm";
        else EXPECT_TRUE(defines.empty()) << stepMm << " mm: pow";
        FrameDescription frame = frameLookingAt(glm::dvec3(0), 90, 30, 20, {96, 96}, ShadingMode::Solid);
        frame.raycast.stepMm = stepMm;
        Comparison c = compareWithReference(volume, tf, frame, 300, 7);
        EXPECT_GT(c.nonEmpty, 100);
        EXPECT_LT(c.maxError, 5e-4) << stepMm << " mm step, rms " << c.rmsError;
    }
}

// Gradient opacity is compiled into the ray caster only for a TF that has one (GRADIENT_OPACITY): the
// variant must agree with the reference as closely as the plain one (the 256-entry gradient table is exact
// for this piecewise-linear ramp, whose only kink is its last point), and it must change the picture.
// Each light count is its own program (phong.glsl's LIGHT_COUNT): none, two and the most, with their own
// directions and colours, match the reference as one light does, and every light shows in the picture.
TEST(Raycast, PhongWithNoneTwoAndFourLightsMatchesCpuReference) {
    glContext();
    glm::ivec3 dims(40);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::Float32, blobs);
    const std::vector<Light> all = {Light{{0.3, 0.5, 1.0}, {1.0, 0.9, 0.8}, true}, Light{{-0.8, 0.2, 0.4}, {0.2, 0.3, 0.9}, true},
                                    Light{{0.0, -1.0, 0.2}, {0.5, 0.1, 0.1}, false}, Light{{0.6, 0.6, -0.3}, {0.1, 0.6, 0.2}, false}};
    double previousMean = -1;
    for (std::size_t count : {std::size_t(0), std::size_t(2), std::size_t(4)}) {
        FrameDescription frame = frameLookingAt(glm::dvec3(0), 90, 30, 20, {96, 96}, ShadingMode::Phong);
        frame.lights.assign(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(count));
        Comparison c = compareWithReference(volume, blobTransferFunction(), frame, 300, 7);
        EXPECT_GT(c.nonEmpty, 100);
        EXPECT_LT(c.maxError, 5e-4) << count << " lights, rms " << c.rmsError;
        double mean = 0;
        for (const glm::vec4& p : c.image.pixels) mean += p.r + p.g + p.b;
        EXPECT_GT(mean, previousMean) << count << " lights: each light adds light";
        previousMean = mean;
    }
}

TEST(Raycast, GradientOpacityMatchesCpuReference) {
    glContext();
    glm::ivec3 dims(40);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::Float32, blobs);
    TransferFunction withGradient = blobTransferFunction();
    withGradient.gradientOpacity = {{0, 0.0}, {40, 1.0}};
    ASSERT_TRUE(withGradient.hasGradientOpacity());
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong}) {
        FrameDescription frame = frameLookingAt(glm::dvec3(0), 90, 30, 20, {96, 96}, mode);
        Comparison c = compareWithReference(volume, withGradient, frame, 300, 17);
        EXPECT_GT(c.nonEmpty, 100);
        EXPECT_LT(c.maxError, 5e-4) << shadingModeName(mode) << " rms " << c.rmsError;

        Renderer plain(glContext(), volume, blobTransferFunction());
        plain.render(frame);
        Image a = plain.readImage();
        const Image& b = c.image;
        double largest = 0;
        for (std::size_t i = 0; i < a.pixels.size(); ++i) largest = std::max(largest, double(std::abs(a.pixels[i].a - b.pixels[i].a)));
        EXPECT_GT(largest, 0.05) << "gradient opacity must thin out the flat interiors";
    }
}

// UInt8 storage: llvmpipe filters R8 textures in 8-bit fixed point (weights and results quantised to
// 1/256 of a texel step, and the result to 1/255), so an interpolated value may differ from the exact one by
// up to ~1 value unit of 255. Through a TF slope of at most 0.35/80 per unit and Phong gradients built from
// such differences, the bound on a composited channel is 2e-2; the RMS must stay well below it (5e-3).
// Measured: solid max 3.3e-3 / rms 4.9e-4, phong max 1.5e-2 / rms 1.5e-3.
TEST(Raycast, MatchesCpuReferenceUInt8Volume) {
    glContext();
    glm::ivec3 dims(40);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, blobs);
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong}) {
        FrameDescription frame = frameLookingAt(glm::dvec3(0), 90, -40, -15, {96, 96}, mode);
        Comparison c = compareWithReference(volume, blobTransferFunction(), frame, 300, 11);
        EXPECT_GT(c.nonEmpty, 100);
        EXPECT_LT(c.maxError, 2e-2) << shadingModeName(mode);
        EXPECT_LT(c.rmsError, 5e-3) << shadingModeName(mode);
    }
}

TEST(Raycast, JitterIsDeterministicAndMatchesReference) {
    glContext();
    glm::ivec3 dims(40);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::Float32, blobs);
    FrameDescription frame = frameLookingAt(glm::dvec3(0), 120, 10, 5, {64, 64}, ShadingMode::Solid);
    frame.raycast.jitterSeed = 1234;
    Renderer renderer(glContext(), volume, blobTransferFunction());
    renderer.render(frame);
    Image a = renderer.readImage();
    renderer.render(frame);
    Image b = renderer.readImage();
    EXPECT_EQ(0, std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec4)));
    Comparison c = compareWithReference(volume, blobTransferFunction(), frame, 200, 3);
    EXPECT_LT(c.maxError, 5e-4);
    // A different seed moves the samples, so the image changes.
    frame.raycast.jitterSeed = 99;
    renderer.render(frame);
    Image d = renderer.readImage();
    EXPECT_NE(0, std::memcmp(a.pixels.data(), d.pixels.data(), a.pixels.size() * sizeof(glm::vec4)));
}

// Empty-space skipping must not change a single bit: it skips only samples the TF makes transparent and
// keeps the sample lattice.
TEST(Raycast, EmptySpaceSkippingChangesNothing) {
    glContext();
    glm::ivec3 dims(48, 40, 36);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims, {0.9, 1.1, 1.3}), ScalarType::UInt8, blobs);
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong}) {
        FrameDescription frame = frameLookingAt(glm::dvec3(1, -2, 0), 110, 65, 35, {80, 72}, mode);
        frame.raycast.jitterSeed = 5;
        Renderer renderer(glContext(), volume, blobTransferFunction());
        frame.raycast.skipEmptySpace = false;
        renderer.render(frame);
        Image full = renderer.readImage();
        frame.raycast.skipEmptySpace = true;
        renderer.setCountSamples(true);
        renderer.render(frame);
        Image skipped = renderer.readImage();
        std::uint64_t samplesWithSkipping = renderer.samplesLastFrame();
        frame.raycast.skipEmptySpace = false;
        renderer.render(frame);
        std::uint64_t samplesWithout = renderer.samplesLastFrame();
        EXPECT_EQ(0, std::memcmp(full.pixels.data(), skipped.pixels.data(), full.pixels.size() * sizeof(glm::vec4)));
        EXPECT_LT(samplesWithSkipping, samplesWithout) << "skipping must skip something here";
    }
}

// The distance map lets one jump cross many empty bricks: the same samples, the same image bit for bit, and
// fewer steps of the rays' loops than jumping one brick at a time.
TEST(Raycast, JumpingOverManyEmptyBricksAtOnceChangesNothingButTheSteps) {
    glContext();
    glm::ivec3 dims(64, 56, 48);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims, {0.9, 1.1, 1.3}), ScalarType::UInt8, blobs);
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong}) {
        FrameDescription frame = frameLookingAt(glm::dvec3(1, -2, 0), 130, 65, 35, {80, 72}, mode);
        frame.raycast.jitterSeed = 7;
        frame.raycast.skipEmptySpace = true;
        Renderer renderer(glContext(), volume, blobTransferFunction());
        renderer.setCountSamples(true);
        auto run = [&](int limit) {
            renderer.setEmptySpaceJumpLimit(limit);
            renderer.render(frame);
            return std::tuple{renderer.readImage(), renderer.samplesLastFrame(), renderer.rayStepsLastFrame()};
        };
        auto [oneBrick, samplesOne, stepsOne] = run(1);
        auto [distanceMap, samplesMap, stepsMap] = run(255);
        EXPECT_EQ(0, std::memcmp(oneBrick.pixels.data(), distanceMap.pixels.data(), oneBrick.pixels.size() * sizeof(glm::vec4)));
        EXPECT_EQ(samplesOne, samplesMap);
        EXPECT_LT(stepsMap, stepsOne) << "the blobs leave empty regions several bricks wide";
        EXPECT_GT(stepsMap, samplesMap) << "every sample is a step, and some steps are jumps";
    }
}

// Inside a clip mesh the ray walks every lattice sample (raycast.comp: no jump while a mesh holds the last
// sample), so the first sample past a crossing, where the cut face is worked out, is the same with and without
// empty-space skipping. Spheres placed at random over the blobs' edges, where a mesh's far side meets both
// empty bricks and tissue: the image with skipping is the one without, bit for bit.
TEST(Raycast, CutFacesAreTheSameWithAndWithoutEmptySpaceSkipping) {
    glContext();
    glm::ivec3 dims(48, 44, 40);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims, {0.9, 1.1, 1.3}), ScalarType::UInt8, blobs);
    Renderer renderer(glContext(), volume, blobTransferFunction());
    renderer.setCountSamples(true);
    std::mt19937 random(12);
    std::uniform_real_distribution<double> position(-20.0, 20.0), radius(3.0, 9.0);
    clip::ClipMeshSet& set = renderer.clipMeshes();
    for (int i = 0; i < 6; ++i)
        set.add(std::make_shared<const clip::TriangleMesh>(clip::makeSphere(radius(random), 3)), glm::dvec3(1.0),
                clip::RigidPose{{position(random), position(random), position(random)}, {}}, "sphere " + std::to_string(i));
    set.update();
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong})
        for (double azimuth : {20.0, 110.0, 200.0, 290.0}) {
            FrameDescription frame = frameLookingAt(glm::dvec3(1, -2, 0), 110, azimuth, 25, {80, 72}, mode);
            frame.raycast.jitterSeed = 5;
            frame.raycast.cutFace.enabled = true;
            auto run = [&](bool skip) {
                frame.raycast.skipEmptySpace = skip;
                renderer.render(frame);
                return std::pair{renderer.readImage(), renderer.rayStepsLastFrame()};
            };
            auto [walked, stepsWalked] = run(false);
            auto [skipped, stepsSkipped] = run(true);
            SCOPED_TRACE(std::string(shadingModeName(mode)) + ", azimuth " + std::to_string(azimuth));
            EXPECT_EQ(0, std::memcmp(walked.pixels.data(), skipped.pixels.data(), walked.pixels.size() * sizeof(glm::vec4)));
            EXPECT_LT(stepsSkipped, stepsWalked) << "the view has empty space to skip";
        }
}

// The ray caster tests a sample against the clip maps only inside the ray's span (clip_test.glsl,
// rayClipSpan), and a ray that meets no mesh's depth box takes the sample loop without clip tests (raycast.comp
// castRay): the image is the one that tests every sample against every mesh, bit for bit, with and without
// cut faces, for a sphere, a turned box, a torus (two intervals) turned off the axes and a box that reaches out
// of the volume, from two sides.
TEST(Raycast, ClipTestsOnlyInTheRaysSpanChangeNoPixel) {
    glContext();
    glm::ivec3 dims(48, 44, 40);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims, {0.9, 1.1, 1.3}), ScalarType::UInt8, blobs);
    Renderer renderer(glContext(), volume, blobTransferFunction());
    renderer.setCountSamples(true);
    auto mesh = [](clip::TriangleMesh m) { return std::make_shared<const clip::TriangleMesh>(std::move(m)); };
    auto turned = [](glm::dvec3 at, double angleDeg, glm::dvec3 axis) {
        return clip::RigidPose{at, glm::angleAxis(glm::radians(angleDeg), glm::normalize(axis))};
    };
    clip::ClipMeshSet& set = renderer.clipMeshes();
    set.add(mesh(clip::makeSphere(7, 3)), glm::dvec3(1.0), clip::RigidPose{{4, -3, 2}, {}}, "sphere");
    set.add(mesh(clip::makeBox({9, 6, 12})), glm::dvec3(1.0), turned({-9, 6, -3}, 37, {1, 2, 0.5}), "turned box");
    set.add(mesh(clip::makeTorus(8, 2.5, 48, 16)), glm::dvec3(1.0), turned({2, 10, -8}, 71, {0.3, -1, 1}), "torus");
    set.add(mesh(clip::makeBox({30, 8, 8})), glm::dvec3(1.0), clip::RigidPose{{18, -12, 10}, {}}, "box out of the volume");
    set.update();
    int images = 0;
    for (bool cutFaces : {false, true})
        for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong})
            for (double azimuth : {65.0, 230.0}) {
                FrameDescription frame = frameLookingAt(glm::dvec3(1, -2, 0), 110, azimuth, 35, {72, 64}, mode);
                frame.raycast.jitterSeed = 3;
                frame.raycast.cutFace.enabled = cutFaces;
                auto run = [&](bool spans) {
                    renderer.clipMeshes().setDepthBoxTests(spans);
                    renderer.render(frame);
                    return std::pair{renderer.readImage(), renderer.samplesLastFrame()};
                };
                auto [everySample, samplesEvery] = run(false);
                auto [inSpans, samplesInSpans] = run(true);
                SCOPED_TRACE(std::string(shadingModeName(mode)) + (cutFaces ? ", cut faces" : "") + ", azimuth " + std::to_string(azimuth));
                EXPECT_EQ(0, std::memcmp(everySample.pixels.data(), inSpans.pixels.data(), everySample.pixels.size() * sizeof(glm::vec4)));
                EXPECT_EQ(samplesEvery, samplesInSpans);
                ++images;
            }
    EXPECT_EQ(images, 8);
    // The meshes do carve this view: without them the image is another.
    FrameDescription frame = frameLookingAt(glm::dvec3(1, -2, 0), 110, 65, 35, {72, 64}, ShadingMode::Phong);
    frame.raycast.jitterSeed = 3;
    renderer.render(frame);
    Image carved = renderer.readImage();
    for (int i = set.count() - 1; i >= 0; --i) set.remove(i);
    set.update();
    renderer.render(frame);
    Image whole = renderer.readImage();
    EXPECT_NE(0, std::memcmp(carved.pixels.data(), whole.pixels.data(), carved.pixels.size() * sizeof(glm::vec4)));
}

// The tile order (shaders/tile_order.glsl) changes only which workgroup shades which pixels: every pixel is
// shaded once, to the same value, for any band height, at sizes the tiles and bands do not divide. A close-up
// fills the image with tissue, and the renderer with bands first shows it with another jitter, so a pixel it
// failed to shade would keep that frame's value.
TEST(Raycast, TileOrderShadesEveryPixelOnceAndChangesNoPixel) {
    glContext();
    glm::ivec3 dims(40, 36, 32);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims, {0.9, 1.1, 1.3}), ScalarType::UInt8, blobs);
    for (glm::ivec2 size : {glm::ivec2(80, 72), glm::ivec2(37, 129)}) {
        FrameDescription frame = frameLookingAt(glm::dvec3(1, -2, 0), 32, 65, 35, size, ShadingMode::Phong);
        frame.raycast.jitterSeed = 5;
        FrameDescription other = frame;
        other.raycast.jitterSeed = 6;
        Renderer scanline(glContext(), volume, blobTransferFunction());
        scanline.setTileRowsPerBand(1);
        scanline.render(frame);
        Image expected = scanline.readImage();
        for (int rows : {2, 3, 4, 16}) {
            Renderer banded(glContext(), volume, blobTransferFunction());
            banded.setTileRowsPerBand(rows);
            banded.render(other);
            banded.render(frame);
            Image image = banded.readImage();
            EXPECT_EQ(0, std::memcmp(expected.pixels.data(), image.pixels.data(), expected.pixels.size() * sizeof(glm::vec4)))
                << size.x << "x" << size.y << ", " << rows << " rows per band";
        }
        // Independent of the order: from inside uniform tissue every ray meets tissue at once, so every pixel
        // must be coloured (a pixel no group shaded stays transparent black).
        VolumeData uniform = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, [](glm::dvec3) { return 220.0; });
        FrameDescription inside = frameLookingAt(glm::dvec3(0, 0, 0), 2, 30, 20, size, ShadingMode::Solid);
        Renderer banded(glContext(), uniform, blobTransferFunction());
        banded.render(inside);
        Image image = banded.readImage();
        int uncoloured = 0;
        for (int y = 0; y < size.y; ++y)
            for (int x = 0; x < size.x; ++x) uncoloured += image.at(x, y).a < 0.5f;
        EXPECT_EQ(uncoloured, 0) << size.x << "x" << size.y;
    }
}

// Two worker threads each take one half of the dispatch: in bands of two rows, one takes the first and the other
// the second row of every band, so their work is nearly equal, where scanline order gives one the top and the
// other the bottom.
TEST(Raycast, BandedTileOrderBalancesTheHalvesOfTheDispatch) {
    glContext();
    glm::ivec3 dims(48, 40, 36);
    // Tissue only in the lower part of the volume: rays through the upper part of the image cost little.
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8,
                                         [](glm::dvec3 p) { return p.z < 0.0 ? blobs(p) : 0.0; });
    // An oblique view: looking along an axis, rows of tiles alias with the rows of bricks, and every other row
    // of tiles costs more (bands of two rows then split 1.06 : 1 with bricks of 4 voxels).
    FrameDescription frame = frameLookingAt(glm::dvec3(0, 0, 0), 120, 25, 15, {192, 192}, ShadingMode::Solid);
    auto imbalance = [&](int rowsPerBand) {
        Renderer renderer(glContext(), volume, blobTransferFunction());
        renderer.setCountSamples(true);
        renderer.setTileRowsPerBand(rowsPerBand);
        renderer.render(frame);
        glm::dvec2 halves = renderer.rayStepsByDispatchHalf();
        return std::max(halves.x, halves.y) / (0.5 * (halves.x + halves.y));
    };
    double scanline = imbalance(1), banded = imbalance(2);
    EXPECT_GT(scanline, 1.3) << "the scene must load the halves unequally for this test to mean anything";
    EXPECT_LT(banded, 1.05) << "scanline order: " << scanline;
}

// An opaque sphere of radius R covers exactly the pixels whose ray passes within R of its centre.
TEST(Raycast, OpaqueSphereCoversAnalyticPixelCount) {
    glContext();
    const double radius = 14.0;
    glm::ivec3 dims(48);
    // The value crosses 127.5 exactly at |p| = radius and changes 255/3 per mm around it.
    auto sphere = [&](glm::dvec3 p) { return 127.5 - (glm::length(p) - radius) * 85.0; };
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::Float32, sphere);
    TransferFunction tf;
    tf.color = {{0, glm::dvec3(1)}};
    tf.opacity = {{127.4, 0.0}, {127.6, 1.0}};
    FrameDescription frame = frameLookingAt(glm::dvec3(0.3, -0.2, 0.1), 150, 20, 10, {160, 160}, ShadingMode::Solid);
    frame.raycast.stepMm = 0.05;
    Renderer renderer(glContext(), volume, tf);
    renderer.render(frame);
    Image image = renderer.readImage();

    double aspect = 1.0;
    glm::dmat4 inverseViewProjection = glm::inverse(frame.camera.projection(aspect) * frame.camera.view());
    glm::dvec3 eye = frame.camera.position();
    int expected = 0, rendered = 0;
    for (int y = 0; y < frame.size.y; ++y)
        for (int x = 0; x < frame.size.x; ++x) {
            glm::dvec2 ndc = (glm::dvec2(x, y) + 0.5) / glm::dvec2(frame.size) * 2.0 - 1.0;
            ndc.y = -ndc.y;
            glm::dvec4 far = inverseViewProjection * glm::dvec4(ndc, 1, 1);
            glm::dvec3 d = glm::normalize(glm::dvec3(far) / far.w - eye);
            glm::dvec3 toCentre = -eye;
            double distance = glm::length(toCentre - glm::dot(toCentre, d) * d);
            expected += distance < radius;
            rendered += image.at(x, y).a > 0.5f;
        }
    // The silhouette's radius in pixels, and the tolerance: trilinear interpolation of this linear ramp moves
    // the threshold surface by far less than 0.25 mm, i.e. a ring of width 0.25 mm at the silhouette.
    double pixelsPerMm = frame.size.y / (2.0 * 150 * std::tan(glm::radians(15.0)));
    double rho = radius * pixelsPerMm;
    double tolerance = 2 * std::numbers::pi * rho * 0.25 * pixelsPerMm;
    EXPECT_NEAR(rendered, expected, tolerance) << "expected " << expected << " (pi rho^2 = " << std::numbers::pi * rho * rho << ")";
    EXPECT_GT(expected, 1000);
}

// The same object stored in an oblique, anisotropic volume renders like the axis-aligned volume it was
// resampled from.
TEST(Raycast, ObliqueVolumeRendersSameObjectAsAxisAligned) {
    glContext();
    auto object = [](glm::dvec3 p) {
        // An ellipsoid (semi-axes 14, 9, 7 mm) rotated about z, blended with a 6 mm ball off to the side.
        glm::dvec3 q(0.8 * p.x + 0.6 * p.y, -0.6 * p.x + 0.8 * p.y, p.z);
        double e = glm::length(q / glm::dvec3(14, 9, 7));
        double b = glm::length(p - glm::dvec3(-9, 10, 6)) / 6.0;
        return 255.0 * std::clamp(1.5 - std::min(e, b), 0.0, 1.0);
    };
    glm::ivec3 dims(48);
    VolumeData aligned = test::makeVolume(dims, test::centredAffine(dims), ScalarType::Float32, object);
    // Oblique: rotated 30 degrees about x then 20 about z, spacings 0.8 x 1.0 x 1.25 mm, centred.
    glm::dmat3 rx(1, 0, 0, 0, std::cos(0.5236), std::sin(0.5236), 0, -std::sin(0.5236), std::cos(0.5236));
    glm::dmat3 rz(std::cos(0.349), std::sin(0.349), 0, -std::sin(0.349), std::cos(0.349), 0, 0, 0, 1);
    glm::dvec3 spacing(0.8, 1.0, 1.25);
    glm::ivec3 obliqueDims(60, 48, 40);
    glm::dmat3 linear = rz * rx * glm::dmat3(glm::dvec3(spacing.x, 0, 0), glm::dvec3(0, spacing.y, 0), glm::dvec3(0, 0, spacing.z));
    glm::dmat4 affine(linear);
    affine[3] = glm::dvec4(-linear * (0.5 * glm::dvec3(obliqueDims - 1)), 1.0);
    VolumeData oblique = test::makeVolume(obliqueDims, affine, ScalarType::Float32, object);

    TransferFunction tf = test::rampTransferFunction(60, 200, 0.6);
    for (auto [azimuth, elevation] : {std::pair{0.0, 0.0}, {70.0, 30.0}, {200.0, -45.0}}) {
        FrameDescription frame = frameLookingAt(glm::dvec3(0), 140, azimuth, elevation, {96, 96}, ShadingMode::Solid);
        Renderer a(glContext(), aligned, tf), b(glContext(), oblique, tf);
        frame.raycast.stepMm = 0.4;
        a.render(frame);
        b.render(frame);
        Image ia = a.readImage(), ib = b.readImage();
        int silhouetteA = 0, silhouetteB = 0, both = 0;
        double sum = 0;
        for (std::size_t i = 0; i < ia.pixels.size(); ++i) {
            bool inA = ia.pixels[i].a > 0.05f, inB = ib.pixels[i].a > 0.05f;
            silhouetteA += inA, silhouetteB += inB, both += inA && inB;
            double d = ia.pixels[i].a - ib.pixels[i].a;
            sum += d * d;
        }
        double iou = double(both) / (silhouetteA + silhouetteB - both);
        double rms = std::sqrt(sum / static_cast<double>(ia.pixels.size()));
        // Both volumes sample the same smooth function at <= 1.25 mm; the reconstructions differ by the
        // interpolation error of a field whose value changes 255/7 per mm over at most 0.6 mm of
        // misalignment: a few percent of opacity at most, hence RMS alpha < 0.02 and IoU > 0.97.
        EXPECT_GT(iou, 0.97) << "azimuth " << azimuth;
        EXPECT_LT(rms, 0.02) << "azimuth " << azimuth;
        EXPECT_GT(silhouetteA, 500);
    }
}

// One axis over GL_MAX_3D_TEXTURE_SIZE is folded (FoldedVolume.*); two cannot be, and are an InputError naming
// the file and the dimensions before anything is allocated.
TEST(Raycast, VolumeLargerThanTextureLimitOnTwoAxesIsAnInputError) {
    glContext();
    VolumeData huge;
    huge.dims = glm::ivec3(glContext().info().max3DTextureSize + 1, glContext().info().max3DTextureSize + 1, 1);
    huge.source = "huge.nii";
    try {
        GpuVolume gpu(glContext().info(), huge);
        FAIL() << "expected an InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "huge.nii");
        EXPECT_EQ(e.field(), "dim");
    }
}

}  // namespace
}  // namespace curette
