#include "render/model/cut_face_measure.h"

#include <algorithm>
#include <cmath>

namespace curette {

std::vector<double> compositedLuma(const Image& image, glm::vec4 background) {
    std::vector<double> luma(image.pixels.size());
    for (std::size_t i = 0; i < luma.size(); ++i) {
        const glm::vec4& p = image.pixels[i];   // premultiplied
        glm::dvec3 rgb = glm::dvec3(p) + (1.0 - double(p.a)) * double(background.a) * glm::dvec3(background);
        luma[i] = 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b;
    }
    return luma;
}

std::vector<bool> carvedPixels(const Image& carved, const Image& uncarved, glm::vec4 background, double threshold,
                               int erodePx) {
    std::vector<double> a = compositedLuma(carved, background), b = compositedLuma(uncarved, background);
    int w = carved.width, h = carved.height;
    std::vector<bool> differs(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) differs[i] = std::abs(a[i] - b[i]) > threshold;
    std::vector<bool> mask(a.size(), false);
    for (int y = erodePx; y < h - erodePx; ++y)
        for (int x = erodePx; x < w - erodePx; ++x) {
            bool all = true;
            for (int dy = -erodePx; dy <= erodePx && all; ++dy)
                for (int dx = -erodePx; dx <= erodePx && all; ++dx)
                    all = differs[static_cast<std::size_t>((y + dy) * w + x + dx)];
            mask[static_cast<std::size_t>(y * w + x)] = all;
        }
    return mask;
}

double highFrequencyRms(const Image& image, glm::vec4 background, const std::vector<bool>& mask, double sigmaPx) {
    std::vector<double> luma = compositedLuma(image, background);
    int w = image.width, h = image.height, radius = std::max(1, static_cast<int>(std::ceil(3.0 * sigmaPx)));
    std::vector<double> kernel(static_cast<std::size_t>(2 * radius + 1));
    double total = 0;
    for (int i = -radius; i <= radius; ++i) total += kernel[static_cast<std::size_t>(i + radius)] = std::exp(-0.5 * i * i / (sigmaPx * sigmaPx));
    for (double& k : kernel) k /= total;
    auto blur = [&](const std::vector<double>& in, bool horizontal) {
        std::vector<double> out(in.size(), 0.0);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                double sum = 0;
                for (int i = -radius; i <= radius; ++i) {
                    int sx = horizontal ? std::clamp(x + i, 0, w - 1) : x, sy = horizontal ? y : std::clamp(y + i, 0, h - 1);
                    sum += kernel[static_cast<std::size_t>(i + radius)] * in[static_cast<std::size_t>(sy * w + sx)];
                }
                out[static_cast<std::size_t>(y * w + x)] = sum;
            }
        return out;
    };
    std::vector<double> blurred = blur(blur(luma, true), false);
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < luma.size(); ++i)
        if (mask[i]) {
            double d = luma[i] - blurred[i];
            sum += d * d;
            ++count;
        }
    return count ? std::sqrt(sum / static_cast<double>(count)) : 0.0;
}

}  // namespace curette
