#pragma once
// Shared by the tools tests: a PNG read back as RGBA, and the small noisy ball the session tests carve.

#include <cstdint>
#include <filesystem>
#include <vector>

namespace curette::testing {

struct Png {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;   // empty when the file could not be read
};
Png readPng(const std::filesystem::path& path);

// 32^3 voxels: a core (200) inside a shell (120) in air, with noise 0..20 (a fixed seed).
std::vector<std::uint8_t> noisyBallVoxels();

}  // namespace curette::testing
