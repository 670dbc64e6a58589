// The RT Structure Set's contours of a slice (io/slice_contours.h): rasterised back at pixel centres with the
// even-odd rule they give exactly the slice's pixels, and each slice's polygons enclose exactly its pixel area.
#include "io/slice_contours.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace curette::io {
namespace {

// Even-odd point-in-polygon over all polygons (a horizontal ray towards +x), as RT systems rasterise.
bool insideEvenOdd(const std::vector<std::vector<glm::dvec2>>& polygons, glm::dvec2 p) {
    bool inside = false;
    for (const auto& polygon : polygons)
        for (std::size_t v = 0; v < polygon.size(); ++v) {
            glm::dvec2 a = polygon[v], b = polygon[(v + 1) % polygon.size()];
            if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)) inside = !inside;
        }
    return inside;
}

void expectOutlinesGiveBackTheMask(const std::vector<std::uint8_t>& mask, int width, int height) {
    auto polygons = sliceOutlines(mask.data(), width, height);
    double area = 0;
    std::size_t set = 0;
    for (const auto& polygon : polygons) {
        EXPECT_GE(polygon.size(), 4u);
        area += polygonArea(polygon);
        for (const glm::dvec2& p : polygon) {
            EXPECT_EQ(p.x - std::floor(p.x), 0.5) << "vertices are pixel corners";
            EXPECT_EQ(p.y - std::floor(p.y), 0.5);
        }
    }
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i) {
            bool on = mask[std::size_t(j) * width + i] != 0;
            set += on;
            EXPECT_EQ(insideEvenOdd(polygons, glm::dvec2(i, j)), on) << "pixel " << i << ", " << j;
        }
    EXPECT_DOUBLE_EQ(area, double(set)) << "outer boundaries count positive, holes negative";
}

TEST(SliceContours, OnePixelIsOneSquare) {
    std::vector<std::uint8_t> mask(9, 0);
    mask[4] = 1;
    auto polygons = sliceOutlines(mask.data(), 3, 3);
    ASSERT_EQ(polygons.size(), 1u);
    ASSERT_EQ(polygons[0].size(), 4u);
    EXPECT_DOUBLE_EQ(polygonArea(polygons[0]), 1.0);
    EXPECT_EQ(polygons[0][0], glm::dvec2(0.5, 0.5));
}

TEST(SliceContours, ARingHasAnOuterBoundaryAndAHole) {
    std::vector<std::uint8_t> mask(25, 0);
    for (int j = 1; j < 4; ++j)
        for (int i = 1; i < 4; ++i) mask[std::size_t(j) * 5 + i] = !(i == 2 && j == 2);
    auto polygons = sliceOutlines(mask.data(), 5, 5);
    ASSERT_EQ(polygons.size(), 2u);
    EXPECT_DOUBLE_EQ(polygonArea(polygons[0]) + polygonArea(polygons[1]), 8.0);
    expectOutlinesGiveBackTheMask(mask, 5, 5);
}

TEST(SliceContours, PixelsMeetingAtACornerAreSeparatePolygons) {
    std::vector<std::uint8_t> mask = {1, 0, 0, 1};
    auto polygons = sliceOutlines(mask.data(), 2, 2);
    ASSERT_EQ(polygons.size(), 2u);
    for (const auto& polygon : polygons) EXPECT_DOUBLE_EQ(polygonArea(polygon), 1.0);
    expectOutlinesGiveBackTheMask(mask, 2, 2);
}

TEST(SliceContours, RandomMasksComeBackExactly) {
    std::mt19937 random(7);
    for (int trial = 0; trial < 50; ++trial) {
        int width = 1 + int(random() % 17), height = 1 + int(random() % 13);
        double density = double(random() % 100) / 100.0;
        std::vector<std::uint8_t> mask(std::size_t(width) * height);
        for (auto& m : mask) m = double(random() % 1000) / 1000.0 < density;
        expectOutlinesGiveBackTheMask(mask, width, height);
    }
}

TEST(SliceContours, AnEmptySliceHasNoOutline) {
    std::vector<std::uint8_t> mask(12, 0);
    EXPECT_TRUE(sliceOutlines(mask.data(), 4, 3).empty());
}

}  // namespace
}  // namespace curette::io
