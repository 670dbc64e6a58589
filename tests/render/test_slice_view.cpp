// The slice views (render/model/slice_view.h), GL-free: reslices of an analytic ball on an oblique,
// anisotropic grid in world space, the display orientation, the pixel <-> world map, the clip meshes'
// cross-sections against the analytic circle, and the removed-region tint against the field.
#include "render/model/slice_view.h"

#include "mesh/primitives.h"
#include "plan/removal_report.h"
#include "tests/render/gl_test_support.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

namespace curette {
namespace {

const glm::dvec3 kCentre(10.0, -5.0, 20.0);
constexpr double kRadius = 12.0;

// An oblique grid with spacing 0.8 x 1.0 x 1.5 mm, turned 20 degrees about a skew axis, centred on kCentre.
glm::dmat4 obliqueAffine(glm::ivec3 dims) {
    glm::dmat4 rotation = glm::rotate(glm::dmat4(1.0), glm::radians(20.0), glm::normalize(glm::dvec3(1, 2, 3)));
    glm::dmat4 scale = glm::scale(glm::dmat4(1.0), glm::dvec3(0.8, 1.0, 1.5));
    glm::dmat4 centre = glm::translate(glm::dmat4(1.0), -0.5 * glm::dvec3(dims - 1));
    return glm::translate(glm::dmat4(1.0), kCentre) * rotation * scale * centre;
}

// The signed distance to the ball's surface, positive inside: a window of +-0.01 makes it black and white.
VolumeData ballVolume() {
    glm::ivec3 dims(56, 46, 32);
    return test::makeVolume(dims, obliqueAffine(dims), ScalarType::Float32,
                            [](glm::dvec3 p) { return kRadius - glm::length(p - kCentre); });
}

const GreyWindow kSharpWindow{-0.01, 0.01};

SliceOverlays noOverlays() {
    SliceOverlays o;
    o.crosshairLines = false;
    o.orientationLetters = false;
    return o;
}

TEST(SliceView, ReslicesThroughTheCentreShowTheBallsDiscAtItsPlace) {
    VolumeData volume = ballVolume();
    for (SliceAxis axis : kSliceAxes) {
        SliceImage slice = renderSlice(volume, axis, kCentre, kSharpWindow, noOverlays());
        const SlicePlane& plane = slice.plane;
        EXPECT_DOUBLE_EQ(plane.pixelMm, 0.8);
        EXPECT_NEAR(plane.offsetMm(kCentre), 0.0, 1e-9);
        glm::dvec2 sum(0.0);
        double white = 0;
        int misclassified = 0;
        for (int y = 0; y < slice.image.height; ++y)
            for (int x = 0; x < slice.image.width; ++x) {
                glm::dvec2 p(x + 0.5, y + 0.5);
                double grey = slice.image.at(x, y).r;
                double distance = glm::length(plane.worldAt(p) - kCentre);
                // Away from the surface (a tenth of a pixel: trilinear over a distance field is that close) the
                // pixel is white inside and black outside.
                if (distance < kRadius - 0.08 && grey != 1.0f) ++misclassified;
                if (distance > kRadius + 0.08 && grey != 0.0f) ++misclassified;
                sum += grey * p;
                white += grey;
            }
        EXPECT_EQ(misclassified, 0) << sliceAxisName(axis);
        glm::dvec3 centroid = plane.worldAt(sum / white);
        EXPECT_LT(glm::length(centroid - kCentre), 0.5 * plane.pixelMm) << sliceAxisName(axis);
        double radius = std::sqrt(white / M_PI) * plane.pixelMm;
        EXPECT_NEAR(radius, kRadius, 0.5 * plane.pixelMm) << sliceAxisName(axis);
    }
}

TEST(SliceView, AnOffCentreSliceShowsTheSmallerDisc) {
    VolumeData volume = ballVolume();
    const double offset = 7.0;
    SliceImage slice = renderSlice(volume, SliceAxis::Coronal, kCentre + glm::dvec3(0, offset, 0), kSharpWindow, noOverlays());
    double white = 0;
    for (const glm::vec4& p : slice.image.pixels) white += p.r;
    double expected = std::sqrt(kRadius * kRadius - offset * offset);
    EXPECT_NEAR(std::sqrt(white / M_PI) * slice.plane.pixelMm, expected, 0.5 * slice.plane.pixelMm);
}

TEST(SliceView, PixelToWorldAndBackIsTheIdentity) {
    VolumeData volume = ballVolume();
    std::mt19937 random(3);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (SliceAxis axis : kSliceAxes) {
        SlicePlane plane = slicePlane(volume.dims, volume.indexToWorld, axis, kCentre + glm::dvec3(1.3, -2.1, 0.7));
        for (int n = 0; n < 100; ++n) {
            glm::dvec2 p(unit(random) * plane.sizePx.x, unit(random) * plane.sizePx.y);
            glm::dvec3 world = plane.worldAt(p);
            EXPECT_NEAR(plane.offsetMm(world), 0.0, 1e-9);
            glm::dvec2 back = plane.pixelAt(world);
            EXPECT_NEAR(back.x, p.x, 1e-9);
            EXPECT_NEAR(back.y, p.y, 1e-9);
        }
        // A world point off the plane maps to its projection.
        glm::dvec3 off = plane.worldAt({3.25, 4.5}) + 5.0 * plane.normal;
        EXPECT_NEAR(glm::length(plane.pixelAt(off) - glm::dvec2(3.25, 4.5)), 0.0, 1e-9);
    }
}

// Radiological display: the patient's Left (RAS -x) on the image's right in axial and coronal, anterior on
// the left in sagittal, anterior up in axial, superior up in coronal and sagittal.
TEST(SliceView, DisplayOrientationFollowsSlicersConvention) {
    const glm::dvec3 centre(0.0);
    auto blobAt = [&](glm::dvec3 where) {
        return test::makeVolume({40, 40, 40}, test::centredAffine({40, 40, 40}), ScalarType::Float32,
                                [where](glm::dvec3 p) { return glm::length(p - where) < 4.0 ? 1.0 : 0.0; });
    };
    // Where the blob's brightest pixels sit relative to the crosshair's, in pixels.
    auto blobOffset = [&](const VolumeData& volume, SliceAxis axis, glm::dvec3 through) {
        SliceImage slice = renderSlice(volume, axis, through, {0.0, 1.0}, noOverlays());
        glm::dvec2 sum(0.0);
        double weight = 0;
        for (int y = 0; y < slice.image.height; ++y)
            for (int x = 0; x < slice.image.width; ++x) {
                sum += double(slice.image.at(x, y).r) * glm::dvec2(x + 0.5, y + 0.5);
                weight += slice.image.at(x, y).r;
            }
        EXPECT_GT(weight, 0.0);
        return sum / weight - slice.plane.pixelAt(through);
    };
    const glm::dvec3 left(-10, 0, 0), anterior(0, 10, 0), superior(0, 0, 10);
    VolumeData atLeft = blobAt(left), atAnterior = blobAt(anterior), atSuperior = blobAt(superior);
    EXPECT_GT(blobOffset(atLeft, SliceAxis::Axial, centre).x, 8.0);
    EXPECT_GT(blobOffset(atLeft, SliceAxis::Coronal, centre).x, 8.0);
    EXPECT_LT(blobOffset(atAnterior, SliceAxis::Axial, centre).y, -8.0);
    EXPECT_LT(blobOffset(atAnterior, SliceAxis::Sagittal, centre).x, -8.0);
    EXPECT_LT(blobOffset(atSuperior, SliceAxis::Coronal, centre).y, -8.0);
    EXPECT_LT(blobOffset(atSuperior, SliceAxis::Sagittal, centre).y, -8.0);
}

TEST(SliceView, SlicePlanesAreAcrossTheirPatientAxes) {
    SlicePlane axial = slicePlane({10, 10, 10}, glm::dmat4(1.0), SliceAxis::Axial, glm::dvec3(1, 2, 3));
    SlicePlane coronal = slicePlane({10, 10, 10}, glm::dmat4(1.0), SliceAxis::Coronal, glm::dvec3(1, 2, 3));
    SlicePlane sagittal = slicePlane({10, 10, 10}, glm::dmat4(1.0), SliceAxis::Sagittal, glm::dvec3(1, 2, 3));
    EXPECT_EQ(axial.normal, glm::dvec3(0, 0, 1));
    EXPECT_EQ(coronal.normal, glm::dvec3(0, 1, 0));
    EXPECT_EQ(sagittal.normal, glm::dvec3(1, 0, 0));
    EXPECT_EQ(axial.right, glm::dvec3(-1, 0, 0));
    EXPECT_EQ(axial.down, glm::dvec3(0, -1, 0));
    EXPECT_EQ(sagittal.right, glm::dvec3(0, -1, 0));
    EXPECT_EQ(coronal.down, glm::dvec3(0, 0, -1));
    EXPECT_DOUBLE_EQ(axial.topLeft.z, 3.0);
    EXPECT_DOUBLE_EQ(coronal.topLeft.y, 2.0);
    EXPECT_DOUBLE_EQ(sagittal.topLeft.x, 1.0);
    // The grid's bounding box: voxel centres 0..9 plus half a voxel each side.
    EXPECT_EQ(axial.sizePx, glm::ivec2(10, 10));
}

TEST(SliceView, TheNearestVoxelIsTheOneWhoseCentreIsNearest) {
    VolumeData volume = ballVolume();
    const glm::dmat4 worldToIndex = glm::inverse(volume.indexToWorld);
    std::mt19937 random(11);
    std::uniform_real_distribution<double> within(-0.49, 0.49);
    for (int n = 0; n < 200; ++n) {
        glm::ivec3 v(n % volume.dims.x, (n * 7) % volume.dims.y, (n * 13) % volume.dims.z);
        glm::dvec3 index = glm::dvec3(v) + glm::dvec3(within(random), within(random), within(random));
        auto got = nearestVoxel(volume.dims, worldToIndex, glm::dvec3(volume.indexToWorld * glm::dvec4(index, 1.0)));
        ASSERT_TRUE(got);
        EXPECT_EQ(*got, v);
    }
    EXPECT_FALSE(nearestVoxel(volume.dims, worldToIndex, glm::dvec3(volume.indexToWorld * glm::dvec4(-0.51, 3, 3, 1.0))));
    EXPECT_FALSE(nearestVoxel(volume.dims, worldToIndex, glm::dvec3(volume.indexToWorld * glm::dvec4(3, volume.dims.y - 0.49, 3, 1.0))));
}

TEST(SliceView, AMeshCrossSectionLiesOnTheAnalyticCurve) {
    VolumeData volume = ballVolume();
    auto sphere = std::make_shared<clip::TriangleMesh>(clip::makeSphere(6.0));
    // Scaled 1.5x along its local x, then turned 90 degrees about z: an ellipsoid with its long axis along y.
    plan::PosedMesh mesh{sphere, {}, glm::dvec3(1.5, 1.0, 1.0)};
    mesh.pose.position = kCentre + glm::dvec3(2.0, 1.0, -1.5);
    mesh.pose.orientation = glm::angleAxis(glm::radians(90.0), glm::dvec3(0, 0, 1));
    SlicePlane plane = slicePlane(volume.dims, volume.indexToWorld, SliceAxis::Axial, kCentre);
    const double dz = kCentre.z - mesh.pose.position.z;
    const double shrink = std::sqrt(1.0 - dz * dz / 36.0);   // the ellipse of the section
    const double a = 6.0 * shrink, b = 9.0 * shrink;        // semi-axes along x and y
    auto curveDistanceMm = [&](glm::dvec3 p) {   // approximately, for points near the ellipse
        glm::dvec2 d(p.x - mesh.pose.position.x, p.y - mesh.pose.position.y);
        double level = std::sqrt(d.x * d.x / (a * a) + d.y * d.y / (b * b));
        return std::abs(level - 1.0) * glm::length(d) / level;
    };
    auto segments = meshCrossSection(mesh, plane);
    ASSERT_GT(segments.size(), 50u);
    for (const auto& [p, q] : segments) {
        EXPECT_NEAR(plane.offsetMm(p), 0.0, 1e-9);
        EXPECT_LT(curveDistanceMm(p), 0.5 * plane.pixelMm);
        EXPECT_LT(curveDistanceMm(q), 0.5 * plane.pixelMm);
    }
    // Drawn: every mesh-coloured pixel lies within a pixel of the curve, and the curve is drawn all round.
    SliceOverlays overlays = noOverlays();
    overlays.meshes.push_back({mesh, true});
    SliceImage slice = renderSlice(volume, SliceAxis::Axial, kCentre, kSharpWindow, overlays);
    int drawn = 0;
    for (int y = 0; y < slice.image.height; ++y)
        for (int x = 0; x < slice.image.width; ++x)
            if (glm::vec3(slice.image.at(x, y)) == kHeldMeshColor) {
                ++drawn;
                EXPECT_LT(curveDistanceMm(plane.worldAt({x + 0.5, y + 0.5})), plane.pixelMm);
            }
    EXPECT_GT(drawn, 50);
    for (int k = 0; k < 64; ++k) {
        double angle = 2 * M_PI * k / 64;
        glm::dvec3 onCurve = mesh.pose.position + glm::dvec3(a * std::cos(angle), b * std::sin(angle), dz);
        glm::dvec2 p = plane.pixelAt(onCurve);
        glm::ivec2 pixel(glm::floor(p));
        bool near = false;   // the pixel the point falls in, or one beside it (the point may sit on a pixel edge)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) near = near || glm::vec3(slice.image.at(pixel.x + dx, pixel.y + dy)) == kHeldMeshColor;
        EXPECT_TRUE(near) << "angle " << angle;
    }
}

TEST(SliceView, RemovedTintIsExactlyWhereTheFieldRemoves) {
    VolumeData volume = ballVolume();
    plan::RemovalField field;
    field.gridDims = volume.dims;
    field.indexToWorld = volume.indexToWorld;
    field.origin = {10, 8, 5};
    field.size = {30, 25, 20};
    field.samplesPerVoxel = 9;
    std::mt19937 random(7);
    std::uniform_int_distribution<int> count(0, 9);
    field.insideSamples.resize(field.box().voxelCount());
    for (std::uint16_t& c : field.insideSamples) c = static_cast<std::uint16_t>(count(random));
    std::vector<std::uint8_t> removed = plan::removedRegionOnGrid(field, {});
    const glm::dmat4 worldToIndex = glm::inverse(volume.indexToWorld);
    for (SliceAxis axis : kSliceAxes) {
        glm::dvec3 through = kCentre + glm::dvec3(-1.0, 2.0, 1.0);
        SliceImage plain = renderSlice(volume, axis, through, {-12.0, 12.0}, noOverlays());
        SliceOverlays overlays = noOverlays();
        overlays.removedRegion = &removed;
        SliceImage tinted = renderSlice(volume, axis, through, {-12.0, 12.0}, overlays);
        int removedPixels = 0, wrong = 0;
        for (int y = 0; y < plain.image.height; ++y)
            for (int x = 0; x < plain.image.width; ++x) {
                auto v = nearestVoxel(volume.dims, worldToIndex, plain.plane.worldAt({x + 0.5, y + 0.5}));
                bool isRemoved = v && removed[volume.linearIndex(v->x, v->y, v->z)];
                removedPixels += isRemoved;
                bool changed = plain.image.at(x, y) != tinted.image.at(x, y);
                if (changed != isRemoved) ++wrong;
                if (isRemoved) {   // filled at least with the translucent tint, the outline opaque
                    glm::vec3 fill = glm::mix(glm::vec3(plain.image.at(x, y)), kRemovedColor, kRemovedFillAlpha);
                    glm::vec3 got(tinted.image.at(x, y));
                    if (glm::length(got - fill) > 1e-5f && glm::length(got - kRemovedColor) > 1e-5f) ++wrong;
                }
            }
        EXPECT_GT(removedPixels, 100) << sliceAxisName(axis);
        EXPECT_EQ(wrong, 0) << sliceAxisName(axis);
    }
}

TEST(SliceView, ProtectedLabelsAreOutlinedRedOthersInTheirColour) {
    VolumeData volume = ballVolume();
    LabelMap labels;
    labels.dims = volume.dims;
    labels.indexToWorld = volume.indexToWorld;
    labels.ids.assign(volume.voxelCount(), 0);
    for (int k = 0; k < volume.dims.z; ++k)
        for (int j = 0; j < volume.dims.y; ++j)
            for (int i = 0; i < volume.dims.x; ++i) {
                glm::dvec3 p = glm::dvec3(volume.indexToWorld * glm::dvec4(i, j, k, 1.0));
                labels.ids[volume.linearIndex(i, j, k)] = glm::length(p - kCentre) < 5 ? 2 : p.x > kCentre.x + 8 ? 1 : 0;
            }
    LabelTable table;
    table.entries = {{1, "one", {0.0, 0.0, 1.0, 1.0}}, {2, "two", {0.0, 1.0, 0.0, 1.0}}};
    SliceOverlays overlays = noOverlays();
    overlays.labelSets.push_back(sliceLabelSet(labels, table, {false, true, true}, {2}));
    SliceImage slice = renderSlice(volume, SliceAxis::Axial, kCentre, {100.0, 101.0}, overlays);   // every value below: black
    int red = 0, blue = 0, other = 0;
    for (const glm::vec4& p : slice.image.pixels) {
        glm::vec3 c(p);
        if (c == kProtectedColor) ++red;
        else if (c == glm::vec3(0, 0, 1)) ++blue;
        else if (c != glm::vec3(0)) ++other;
    }
    EXPECT_GT(red, 20);    // the protected ball's outline (a circle of radius 5 mm, 0.8 mm pixels: ~40 pixels)
    EXPECT_LT(red, 120);
    EXPECT_GT(blue, 20);   // the shown label's edge
    EXPECT_EQ(other, 0);
}

TEST(SliceView, OrientationLettersNameTheEdges) {
    VolumeData volume = ballVolume();
    SliceOverlays overlays = noOverlays();
    overlays.orientationLetters = true;
    SliceImage plain = renderSlice(volume, SliceAxis::Sagittal, kCentre, {100.0, 101.0}, noOverlays());
    SliceImage lettered = renderSlice(volume, SliceAxis::Sagittal, kCentre, {100.0, 101.0}, overlays);
    int w = lettered.image.width, h = lettered.image.height;
    // 'A' on the left edge: its crossbar (row 3 of the glyph) is five pixels wide.
    for (int x = 2; x < 7; ++x) EXPECT_EQ(glm::vec3(lettered.image.at(x, h / 2 - 3 + 3)), kLetterColor);
    // 'S' at the top: its first row is .####
    EXPECT_EQ(glm::vec3(lettered.image.at(w / 2 - 2, 2)), glm::vec3(plain.image.at(w / 2 - 2, 2)));
    EXPECT_EQ(glm::vec3(lettered.image.at(w / 2 - 1, 2)), kLetterColor);
}

}  // namespace
}  // namespace curette
