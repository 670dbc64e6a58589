#include "render/reference/volume_sampler.h"

#include "render/model/volume_geometry.h"

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

glm::dvec3 differencesAcross(const NoDataSamples& noData, glm::dvec3 minus, glm::dvec3 centre, glm::dvec3 plus) {
    glm::dvec3 d;
    for (int a = 0; a < 3; ++a) {
        bool below = noData(minus[a]), above = noData(plus[a]);
        d[a] = below ? (above ? 0.0 : 2.0 * (plus[a] - centre[a])) : (above ? 2.0 * (centre[a] - minus[a]) : plus[a] - minus[a]);
    }
    return d;
}

VolumeSampler::VolumeSampler(const VolumeData& volume)
    : volume_(volume), noData_(volume), texelSize_(1.0 / glm::dvec3(volume.dims)),
      gradientToWorld_(VolumeGeometry{volume.dims, volume.indexToWorld}.gradientIndexToWorld() * volume.valueScale) {}

double VolumeSampler::texel(glm::dvec3 tex) const {
    auto at = [this](int i, int j, int k) { return volume_.normalized(volume_.linearIndex(i, j, k)); };
    return sampleTrilinear(at, volume_.dims, tex, Wrap::ClampToEdge);
}

double VolumeSampler::voxelTexel(glm::ivec3 v) const {
    v = glm::clamp(v, glm::ivec3(0), volume_.dims - 1);
    return volume_.normalized(volume_.linearIndex(v.x, v.y, v.z));
}

glm::dvec3 VolumeSampler::gradientWorld(glm::dvec3 tex) const {
    glm::dvec3 minus(texel(tex - glm::dvec3(texelSize_.x, 0, 0)), texel(tex - glm::dvec3(0, texelSize_.y, 0)),
                     texel(tex - glm::dvec3(0, 0, texelSize_.z)));
    glm::dvec3 plus(texel(tex + glm::dvec3(texelSize_.x, 0, 0)), texel(tex + glm::dvec3(0, texelSize_.y, 0)),
                    texel(tex + glm::dvec3(0, 0, texelSize_.z)));
    glm::dvec3 centre(noData_.any ? texel(tex) : 0.0);  // only the one-sided differences read it
    return gradientToWorld_ * (0.5 * differencesAcross(noData_, minus, centre, plus));
}

glm::dvec3 VolumeSampler::voxelGradientWorld(glm::ivec3 v) const {
    glm::dvec3 minus(voxelTexel(v - glm::ivec3(1, 0, 0)), voxelTexel(v - glm::ivec3(0, 1, 0)), voxelTexel(v - glm::ivec3(0, 0, 1)));
    glm::dvec3 plus(voxelTexel(v + glm::ivec3(1, 0, 0)), voxelTexel(v + glm::ivec3(0, 1, 0)), voxelTexel(v + glm::ivec3(0, 0, 1)));
    return gradientToWorld_ * (0.5 * differencesAcross(noData_, minus, glm::dvec3(voxelTexel(v)), plus));
}

}  // namespace curette::reference
