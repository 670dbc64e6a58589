#include "render/reference/volume_sampler.h"

#include <algorithm>
#include <cmath>

namespace curette::reference {

double sampleTrilinear(const std::function<double(int, int, int)>& texel, glm::ivec3 dims, glm::dvec3 tex, Wrap wrap) {
    glm::dvec3 x = tex * glm::dvec3(dims) - 0.5;  // texel space: texel centres at integers
    glm::dvec3 base = glm::floor(x);
    glm::dvec3 f = x - base;
    glm::ivec3 i0(base);
    auto fetch = [&](int i, int j, int k) {
        if (wrap == Wrap::ZeroBorder) {
            if (i < 0 || j < 0 || k < 0 || i >= dims.x || j >= dims.y || k >= dims.z) return 0.0;
            return texel(i, j, k);
        }
        return texel(std::clamp(i, 0, dims.x - 1), std::clamp(j, 0, dims.y - 1), std::clamp(k, 0, dims.z - 1));
    };
    double result = 0;
    for (int c = 0; c < 8; ++c) {
        int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
        double w = (dx ? f.x : 1 - f.x) * (dy ? f.y : 1 - f.y) * (dz ? f.z : 1 - f.z);
        if (w != 0) result += w * fetch(i0.x + dx, i0.y + dy, i0.z + dz);
    }
    return result;
}

double Grid::sample(glm::dvec3 tex, Wrap wrap) const {
    return sampleTrilinear([this](int i, int j, int k) { return at(i, j, k); }, dims, tex, wrap);
}

}  // namespace curette::reference
