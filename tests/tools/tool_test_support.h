#pragma once
// Shared by the tools tests: a PNG read back as RGBA, the small noisy ball the session tests carve, and the
// removal digest a command prints.

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace curette::testing {

struct Png {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;   // empty when the file could not be read
};
Png readPng(const std::filesystem::path& path);

// 32^3 voxels: a core (200) inside a shell (120) in air, with noise 0..20 (a fixed seed).
std::vector<std::uint8_t> noisyBallVoxels();

// The noisy ball as dir/ball.raw (2 mm voxels) and dir/scene.json: an LAO scene at 48 x 48 with a TF that shows
// core and shell and cheap AO settings, with `changes` merged in (JSON merge patch: clip meshes, shading, ...).
std::filesystem::path writeNoisyBallScene(const std::filesystem::path& dir, const nlohmann::json& changes);

// The removal's SHA-256 in a command's output ("removal <64 hex digits>": record, replay); empty when absent.
std::string removalDigest(const std::string& output);

}  // namespace curette::testing
