#include "mesh/coverage.h"

namespace curette::clip {

std::vector<glm::dvec3> antiAliasingOffsets(int count) {
    auto halton = [](int index, int base) {
        double f = 1, r = 0;
        for (int i = index; i > 0; i /= base) f /= base, r += f * (i % base);
        return r;
    };
    std::vector<glm::dvec3> offsets;
    for (int i = 1; i <= count; ++i) offsets.emplace_back(glm::dvec3(2 * halton(i, 2) - 1, 2 * halton(i, 3) - 1, 2 * halton(i, 5) - 1) * kCellSampleHalfWidth);
    return offsets;
}

int insideSampleCountInIndexSpace(const std::function<bool(glm::dvec3 index)>& insideAtIndex, glm::dvec3 centreIndex,
                                  const std::vector<glm::dvec3>& offsets) {
    // Algorithm 2 lines 3-5: the centre and the eight corners of the voxel's (inset) cell.
    int inside = insideAtIndex(centreIndex) ? 1 : 0;
    for (int corner = 0; corner < 8; ++corner) {
        const double h = kCellSampleHalfWidth;
        glm::dvec3 o((corner & 1) ? h : -h, (corner & 2) ? h : -h, (corner & 4) ? h : -h);
        inside += insideAtIndex(centreIndex + o) ? 1 : 0;
    }
    const int extra = static_cast<int>(offsets.size());
    if (inside == 0) return 0;
    if (inside == 9) return 9 + extra;
    // Lines 8-10: the nine disagree, so the voxel straddles the clip surface; refine with the N offsets.
    for (const glm::dvec3& o : offsets) inside += insideAtIndex(centreIndex + o) ? 1 : 0;
    return inside;
}

int insideSampleCount(const std::function<bool(glm::dvec3 world)>& inside, const glm::dmat4& indexToWorld,
                      glm::dvec3 centreIndex, const std::vector<glm::dvec3>& offsets) {
    return insideSampleCountInIndexSpace(
        [&](glm::dvec3 index) { return inside(glm::dvec3(indexToWorld * glm::dvec4(index, 1.0))); }, centreIndex, offsets);
}

}  // namespace curette::clip
