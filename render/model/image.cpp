#include "render/model/image.h"

#include "base/atomic_file.h"
#include "base/error.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace curette {

namespace {

std::uint8_t toByte(float v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }


}  // namespace

std::vector<std::uint8_t> toRgba8(const Image& image, glm::vec4 background) {
    std::vector<std::uint8_t> out(image.pixels.size() * 4);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        glm::vec4 p = image.pixels[i];
        // Porter-Duff "over" with premultiplied source and straight background.
        float a = p.a + (1.0f - p.a) * background.a;
        glm::vec3 premultiplied = glm::vec3(p) + (1.0f - p.a) * background.a * glm::vec3(background);
        glm::vec3 straight = a > 0.0f ? premultiplied / a : glm::vec3(0.0f);
        out[4 * i + 0] = toByte(straight.r);
        out[4 * i + 1] = toByte(straight.g);
        out[4 * i + 2] = toByte(straight.b);
        out[4 * i + 3] = toByte(a);
    }
    return out;
}

void writePng(const std::filesystem::path& path, const Image& image, glm::vec4 background) {
    writePngRgba8(path, image.width, image.height, toRgba8(image, background));
}

std::vector<std::uint8_t> encodePng(int width, int height, const std::vector<std::uint8_t>& rgba) {
    std::vector<std::uint8_t> encoded;
    auto sink = [](void* context, void* data, int size) {
        auto* bytes = static_cast<std::vector<std::uint8_t>*>(context);
        auto* begin = static_cast<std::uint8_t*>(data);
        bytes->insert(bytes->end(), begin, begin + size);
    };
    if (!stbi_write_png_to_func(sink, &encoded, width, height, 4, rgba.data(), width * 4))
        throw SystemError("PNG encoding of a " + std::to_string(width) + "x" + std::to_string(height) + " image failed");
    return encoded;
}

void writePngRgba8(const std::filesystem::path& path, int width, int height, const std::vector<std::uint8_t>& rgba) {
    std::vector<std::uint8_t> encoded;
    try {
        encoded = encodePng(width, height, rgba);
    } catch (const SystemError& e) {
        throw SystemError(path.string() + ": " + e.what());
    }
    writeFileAtomically(path, encoded);
}

std::string imageHash(const std::vector<std::uint8_t>& rgba8) {
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint8_t b : rgba8) {
        h ^= b;
        h *= 1099511628211ull;
    }
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
    return text;
}

Image meanImage(const std::vector<Image>& images) {
    if (images.empty()) return {};
    Image mean{images[0].width, images[0].height, std::vector<glm::vec4>(images[0].pixels.size(), glm::vec4(0.0f))};
    for (const Image& image : images) {
        if (image.width != mean.width || image.height != mean.height) throw SystemError("meanImage: images of different sizes");
        for (std::size_t i = 0; i < mean.pixels.size(); ++i) mean.pixels[i] += image.pixels[i] / float(images.size());
    }
    return mean;
}

double boxFilteredRmsDifference(const Image& a, const Image& b, int radius) {
    if (a.width != b.width || a.height != b.height) throw SystemError("boxFilteredRmsDifference: images of different sizes");
    double sum = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            glm::dvec3 mean(0.0);
            int count = 0;
            for (int j = std::max(0, y - radius); j <= std::min(a.height - 1, y + radius); ++j)
                for (int i = std::max(0, x - radius); i <= std::min(a.width - 1, x + radius); ++i) {
                    mean += glm::dvec3(a.at(i, j)) - glm::dvec3(b.at(i, j));
                    ++count;
                }
            mean /= double(count);
            sum += glm::dot(mean, mean);
        }
    return a.pixels.empty() ? 0.0 : std::sqrt(sum / (3.0 * double(a.width) * double(a.height)));
}

}  // namespace curette
