#include "render/reference/lao_reference.h"

#include "mesh/coverage.h"

#include <cmath>

namespace curette::reference {

VoxelClipping clipVoxels(const VolumeData& volume, const TransferFunction& tf, const InsideTest& inside,
                         const InsideTest& dilated, const std::vector<glm::dvec3>& offsets) {
    VoxelClipping result;
    result.opacity.dims = volume.dims;
    result.opacity.values.assign(volume.voxelCount(), 0.0);
    result.category.assign(volume.voxelCount(), 0);
    VolumeSampler sampler(volume);
    auto world = [&](glm::dvec3 index) { return glm::dvec3(volume.indexToWorld * glm::dvec4(index, 1.0)); };
    for (int k = 0; k < volume.dims.z; ++k)
        for (int j = 0; j < volume.dims.y; ++j)
            for (int i = 0; i < volume.dims.x; ++i) {
                glm::ivec3 v(i, j, k);
                glm::dvec3 c(v);
                double texel = sampler.voxelTexel(v);
                double alpha = sampler.noData(texel) ? 0.0 : tf.evaluateOpacity(sampler.value(texel));
                if (tf.hasGradientOpacity()) alpha *= tf.evaluateGradientOpacity(glm::length(sampler.voxelGradientWorld(v)));
                // Algorithm 2 lines 3-10 through the one CPU definition of the sample count (mesh/coverage.h).
                const int samples = static_cast<int>(offsets.size()) + 9;
                int visible = samples - clip::insideSampleCount(inside, volume.indexToWorld, c, offsets);
                if (visible == 0) {
                    alpha = 0;
                } else if (visible < samples) {
                    alpha *= double(visible) / double(samples);
                }
                std::size_t index = volume.linearIndex(i, j, k);
                result.opacity.values[index] = alpha;
                result.category[index] = visible == 0 ? 0 : (dilated && !dilated(world(c))) ? 2 : 1;
            }
    return result;
}

double localAmbientOcclusion(const Grid& opacity, const glm::dmat4& worldToTexture, const glm::dmat4& indexToWorld,
                             glm::ivec3 v, const LaoParameters& p) {
    glm::dvec3 centre = glm::dvec3(worldToTexture * (indexToWorld * glm::dvec4(glm::dvec3(v), 1.0)));
    glm::dvec3 margin = 0.5 / glm::dvec3(opacity.dims);
    double exponent = p.stepMm / p.unitLengthMm;
    double ambient = 0;
    for (const LaoDirection& d : p.directions) {
        glm::dvec3 step = glm::dmat3(worldToTexture) * (d.direction * p.stepMm);
        double transmittance = 1, sum = 0;
        for (int m = 1; m <= p.samples; ++m) {
            sum += transmittance;                          // eq. 2, term m
            if (m == p.samples) break;
            glm::dvec3 q = centre + double(m) * step;
            if (glm::any(glm::lessThan(q, -margin)) || glm::any(glm::greaterThan(q, 1.0 + margin))) {
                sum += transmittance * (p.samples - m);
                break;
            }
            double a = opacity.sample(q, Wrap::ZeroBorder);
            transmittance *= std::pow(1.0 - a, exponent);
        }
        ambient += d.weight * sum / p.samples;             // eq. 3 (weights average 1)
    }
    return ambient / static_cast<double>(p.directions.size());
}

}  // namespace curette::reference
