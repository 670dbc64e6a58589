#include "plan/removal_field.h"

#include "base/error.h"
#include "mesh/coverage.h"

#include <cmath>
#include <limits>
#include <string>

namespace curette::plan {

double RemovalField::removedFraction(glm::ivec3 globalIndex) const {
    if (!box().contains(globalIndex)) return 0.0;
    return double(insideSamples[boxIndex(globalIndex)]) / double(samplesPerVoxel);
}

void RemovalField::validate() const {
    const std::string where = "<removal field>";
    if (glm::any(glm::lessThan(size, glm::ivec3(0))) || glm::any(glm::lessThan(origin, glm::ivec3(0))) ||
        glm::any(glm::greaterThan(origin + size, gridDims)))
        throw InputError(where, "box", "a box inside the grid");
    if (insideSamples.size() != box().voxelCount())
        throw InputError(where, "inside_samples", "one count per voxel of the box", std::to_string(insideSamples.size()));
    if (samplesPerVoxel < 9)
        throw InputError(where, "samples_per_voxel", "9 + N with N >= 0", std::to_string(samplesPerVoxel));
    for (std::uint16_t c : insideSamples)
        if (c > samplesPerVoxel) throw InputError(where, "inside_samples", "counts <= samples per voxel", std::to_string(c));
}

RemovalField removalFieldCpu(glm::ivec3 dims, const glm::dmat4& indexToWorld, glm::ivec3 origin, glm::ivec3 size,
                             const InsideTest& inside, const std::vector<glm::dvec3>& offsets) {
    glm::ivec3 lo = glm::clamp(origin, glm::ivec3(0), dims);
    glm::ivec3 hi = glm::clamp(origin + glm::max(size, glm::ivec3(0)), glm::ivec3(0), dims);
    RemovalField field;
    field.gridDims = dims;
    field.indexToWorld = indexToWorld;
    field.origin = lo;
    field.size = hi - lo;
    field.samplesPerVoxel = 9 + static_cast<int>(offsets.size());
    field.insideSamples.assign(field.box().voxelCount(), 0);

    auto insideAtIndex = [&](glm::dvec3 index) { return inside(glm::dvec3(indexToWorld * glm::dvec4(index, 1.0))); };
    for (int k = lo.z; k < hi.z; ++k)
        for (int j = lo.y; j < hi.y; ++j)
            for (int i = lo.x; i < hi.x; ++i) {
                glm::ivec3 v(i, j, k);
                field.insideSamples[field.boxIndex(v)] =
                    static_cast<std::uint16_t>(clip::insideSampleCountInIndexSpace(insideAtIndex, glm::dvec3(v), offsets));
            }
    return field;
}

namespace {

struct PreparedMesh {
    std::shared_ptr<const clip::TriangleMesh> geometry;
    glm::dmat4 worldToPosed;       // inverse(pose)
    glm::dvec3 inverseScale;
    glm::dvec3 boundsMin, boundsMax;  // local
};

}  // namespace

std::vector<glm::dvec3> PosedMesh::worldVertices() const {
    std::vector<glm::dvec3> world;
    if (!geometry) return world;
    const glm::dmat4 toWorld = pose.matrix();
    world.reserve(geometry->positions.size());
    for (const glm::vec3& p : geometry->positions) world.emplace_back(toWorld * glm::dvec4(scale * glm::dvec3(p), 1.0));
    return world;
}

InsideTest insideAnyMesh(std::vector<PosedMesh> meshes) {
    std::vector<PreparedMesh> prepared;
    for (const PosedMesh& m : meshes) {
        if (!m.geometry || m.geometry->triangles.empty()) continue;
        prepared.push_back({m.geometry, m.pose.inverseMatrix(), 1.0 / m.scale, m.geometry->boundsMin(), m.geometry->boundsMax()});
    }
    return [prepared = std::move(prepared)](glm::dvec3 world) {
        for (const PreparedMesh& m : prepared) {
            glm::dvec3 local = glm::dvec3(m.worldToPosed * glm::dvec4(world, 1.0)) * m.inverseScale;
            if (glm::any(glm::lessThan(local, m.boundsMin)) || glm::any(glm::greaterThan(local, m.boundsMax))) continue;
            if (clip::containsPoint(*m.geometry, local)) return true;
        }
        return false;
    };
}

VoxelBox boxAroundMeshes(const std::vector<PosedMesh>& meshes, glm::ivec3 dims, const glm::dmat4& indexToWorld) {
    const glm::dmat4 worldToIndex = glm::inverse(indexToWorld);
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const PosedMesh& m : meshes) {
        if (!m.geometry || m.geometry->triangles.empty()) continue;
        glm::dvec3 bmin = m.geometry->boundsMin(), bmax = m.geometry->boundsMax();
        glm::dmat4 localToWorld = m.pose.matrix();
        for (int c = 0; c < 8; ++c) {
            glm::dvec3 corner((c & 1) ? bmax.x : bmin.x, (c & 2) ? bmax.y : bmin.y, (c & 4) ? bmax.z : bmin.z);
            glm::dvec3 index(worldToIndex * (localToWorld * glm::dvec4(corner * m.scale, 1.0)));
            lo = glm::min(lo, index);
            hi = glm::max(hi, index);
        }
    }
    if (!(lo.x <= hi.x)) return {};
    // Half an index step for the corner samples, the rest for rounding.
    glm::dvec3 first = glm::clamp(glm::floor(lo) - 2.0, glm::dvec3(0.0), glm::dvec3(dims));
    glm::dvec3 last = glm::clamp(glm::ceil(hi) + 3.0, glm::dvec3(0.0), glm::dvec3(dims));
    VoxelBox box{glm::ivec3(first), glm::ivec3(last - first)};
    if (glm::any(glm::lessThanEqual(box.size, glm::ivec3(0)))) return {};
    return box;
}

}  // namespace curette::plan
