#include "tests/tools/tool_test_support.h"

#include "base/atomic_file.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <regex>

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

std::filesystem::path writeNoisyBallScene(const std::filesystem::path& dir, const nlohmann::json& changes) {
    writeFileAtomically(dir / "ball.raw", noisyBallVoxels());
    nlohmann::json scene = nlohmann::json::parse(R"({
  "volume": {"path": "ball.raw", "format": "raw", "raw": {"dims": [32, 32, 32], "type": "uint8", "spacing": [2, 2, 2]}},
  "transfer_function": {"color": [[0, 0, 0, 0], [100, 0.8, 0.6, 0.5], [255, 1, 1, 1]], "opacity": [[0, 0], [60, 0], [100, 0.2], [255, 0.8]]},
  "camera": {"target": "center", "distance_mm": 200, "azimuth_deg": 20, "elevation_deg": 25, "fov_deg": 30},
  "shading": "lao",
  "lights": [{"direction": [0.3, 0.5, 1.0]}],
  "image": {"width": 48, "height": 48},
  "ambient_occlusion": {"rays": "6", "samples": 4, "step_mm": 1.0, "antialiasing_samples": 4}
})");
    scene.merge_patch(changes);
    writeFileAtomically(dir / "scene.json", scene.dump(2));
    return dir / "scene.json";
}

std::string removalDigest(const std::string& output) {
    std::smatch m;
    if (!std::regex_search(output, m, std::regex("removal ([0-9a-f]{64})"))) return {};
    return m[1];
}

}  // namespace curette::testing
