#include "tests/tools/tool_test_support.h"

#include <algorithm>
#include <cmath>
#include <random>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wnull-dereference"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wunused-function"
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

namespace curette::testing {

Png readPng(const std::filesystem::path& path) {
    Png png;
    int channels = 0;
    stbi_uc* data = stbi_load(path.c_str(), &png.width, &png.height, &channels, 4);
    if (!data) return png;
    png.rgba.assign(data, data + static_cast<std::size_t>(png.width) * static_cast<std::size_t>(png.height) * 4);
    stbi_image_free(data);
    return png;
}

std::vector<std::uint8_t> noisyBallVoxels() {
    std::vector<std::uint8_t> voxels(32 * 32 * 32);
    std::mt19937 random(5);
    std::uniform_int_distribution<int> noise(0, 20);
    for (int z = 0; z < 32; ++z)
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                double r = std::sqrt((x - 15.5) * (x - 15.5) + (y - 15.5) * (y - 15.5) + (z - 15.5) * (z - 15.5));
                int v = r < 9 ? 200 : r < 13 ? 120 : 0;
                voxels[static_cast<std::size_t>((z * 32 + y) * 32 + x)] = static_cast<std::uint8_t>(std::min(255, v + noise(random)));
            }
    return voxels;
}

}  // namespace curette::testing
