#pragma once
// Rendered images on the CPU: RGBA float with premultiplied alpha, as the GPU produced them, and their
// conversion to 8-bit PNG (composited over a background, written atomically). Colours are display values,
// as transfer functions specify them (no gamma curve), the convention of VTK and 3D Slicer.

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace curette {

struct Image {
    int width = 0, height = 0;
    std::vector<glm::vec4> pixels;  // row 0 is the top row; premultiplied RGBA
    glm::vec4& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)]; }
    const glm::vec4& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)]; }
};

// 8-bit RGBA (straight alpha) of `image` composited over `background` (straight RGBA).
std::vector<std::uint8_t> toRgba8(const Image& image, glm::vec4 background);

// Writes a PNG atomically; throws SystemError naming the path when it cannot.
void writePng(const std::filesystem::path& path, const Image& image, glm::vec4 background);

// 8-bit RGBA (row 0 at the top) as PNG bytes; throws SystemError when stb cannot encode it.
std::vector<std::uint8_t> encodePng(int width, int height, const std::vector<std::uint8_t>& rgba8);

// Writes 8-bit RGBA (row 0 at the top) as a PNG, atomically.
void writePngRgba8(const std::filesystem::path& path, int width, int height, const std::vector<std::uint8_t>& rgba8);

// How far apart two images of the same size are in structure rather than in noise: the RMS over pixels and
// colour channels of their difference averaged over the (2 radius + 1)^2 box around each pixel (clamped at the
// border). Coherent bands, such as a slab pass's slices where a surface crosses them, survive the average;
// per-pixel jitter noise averages out.
double boxFilteredRmsDifference(const Image& a, const Image& b, int radius);

// The pixel-wise mean of images of the same size (e.g. of one frame over many jitter seeds: its expected image).
Image meanImage(const std::vector<Image>& images);

// FNV-1a 64-bit hash of the 8-bit pixels, printed as 16 hex digits (replays compare these).
std::string imageHash(const std::vector<std::uint8_t>& rgba8);

}  // namespace curette
