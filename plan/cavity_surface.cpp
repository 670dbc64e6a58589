#include "plan/cavity_surface.h"

#include "base/error.h"

#include <array>
#include <unordered_map>
#include <utility>

namespace curette::plan {

namespace {

// The lattice edges a Kuhn tetrahedron can use, as steps from their lower end: the 3 cube edges, the 3 face
// diagonals and the main diagonal (every tetrahedron edge joins corners a <= b componentwise).
constexpr std::array<glm::ivec3, 7> kEdgeSteps{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}}};

int edgeStepIndex(glm::ivec3 step) {
    for (int e = 0; e < 7; ++e)
        if (kEdgeSteps[static_cast<std::size_t>(e)] == step) return e;
    return -1;
}

// The six Kuhn tetrahedra of the unit cube: corner 0, then add the axes in the order of a permutation, ending
// at (1,1,1). Each is the path 0 -> e_a -> e_a + e_b -> 1.
std::array<std::array<glm::ivec3, 4>, 6> kuhnTetrahedra() {
    const std::array<std::array<int, 3>, 6> orders{{{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
    std::array<std::array<glm::ivec3, 4>, 6> tets{};
    for (std::size_t t = 0; t < 6; ++t) {
        glm::ivec3 p(0);
        tets[t][0] = p;
        for (std::size_t s = 0; s < 3; ++s) {
            p[orders[t][s]] = 1;
            tets[t][s + 1] = p;
        }
    }
    return tets;
}

}  // namespace

clip::TriangleMesh isoSurfaceTetrahedra(const VoxelBox& box, const std::vector<double>& values, const glm::dmat4& indexToWorld,
                                        double iso) {
    if (values.size() != box.voxelCount())
        throw InputError("<iso surface>", "values", "one value per voxel of the box", std::to_string(values.size()));
    clip::TriangleMesh mesh;
    mesh.source = "<cavity surface>";
    // Lattice: the box padded by one voxel of zeros on every side.
    const glm::ivec3 origin = box.origin - 1, size = box.size + 2;
    auto value = [&](glm::ivec3 p) {  // p: lattice coordinates (0 .. size - 1)
        glm::ivec3 b = p - 1;
        if (glm::any(glm::lessThan(b, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(b, box.size))) return 0.0;
        return values[(static_cast<std::size_t>(b.z) * static_cast<std::size_t>(box.size.y) + static_cast<std::size_t>(b.y)) *
                          static_cast<std::size_t>(box.size.x) + static_cast<std::size_t>(b.x)];
    };
    auto latticeIndex = [&](glm::ivec3 p) {
        return (static_cast<std::uint64_t>(p.z) * static_cast<std::uint64_t>(size.y) + static_cast<std::uint64_t>(p.y)) *
                   static_cast<std::uint64_t>(size.x) + static_cast<std::uint64_t>(p.x);
    };
    std::unordered_map<std::uint64_t, std::uint32_t> vertexOfEdge;
    // One vertex per crossed lattice edge a -> b (a the lower end), keyed by (a, step).
    auto vertex = [&](glm::ivec3 a, glm::ivec3 b) -> std::uint32_t {
        if (glm::all(glm::lessThanEqual(b, a))) std::swap(a, b);  // tetrahedron edges join comparable corners
        const std::uint64_t key = latticeIndex(a) * 7u + static_cast<std::uint64_t>(edgeStepIndex(b - a));
        auto [it, added] = vertexOfEdge.try_emplace(key, static_cast<std::uint32_t>(mesh.positions.size()));
        if (added) {
            const double fa = value(a), fb = value(b);
            const double t = (iso - fa) / (fb - fa);  // fa, fb on opposite sides of iso, so fb != fa
            const glm::dvec3 index = glm::dvec3(origin + a) + t * glm::dvec3(b - a);
            mesh.positions.emplace_back(glm::dvec3(indexToWorld * glm::dvec4(index, 1.0)));
        }
        return it->second;
    };
    // A mirroring affine (det < 0) turns index-space orientation around in world space.
    const bool mirrored = glm::determinant(glm::dmat3(indexToWorld)) < 0;
    // Emits a triangle (or a quad as two) on the given edges, facing from the inside corners to the outside ones.
    using Edge = std::pair<glm::ivec3, glm::ivec3>;
    auto emit = [&](const std::array<Edge, 4>& edges, int count, glm::dvec3 insideToOutside) {
        // Orientation from the edge midpoints (never degenerate, unlike the interpolated points) in index space.
        auto mid = [&](std::size_t e) { return 0.5 * glm::dvec3(edges[e].first + edges[e].second); };
        const glm::dvec3 normal = glm::cross(mid(1) - mid(0), mid(2) - mid(0));
        bool flip = glm::dot(normal, insideToOutside) < 0;
        if (mirrored) flip = !flip;
        std::array<std::uint32_t, 4> v{};
        for (std::size_t e = 0; e < static_cast<std::size_t>(count); ++e) v[e] = vertex(edges[e].first, edges[e].second);
        auto triangle = [&](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
            mesh.triangles.push_back(flip ? glm::uvec3(x, z, y) : glm::uvec3(x, y, z));
        };
        triangle(v[0], v[1], v[2]);
        if (count == 4) triangle(v[0], v[2], v[3]);
    };
    static const std::array<std::array<glm::ivec3, 4>, 6> tets = kuhnTetrahedra();
    for (int z = 0; z + 1 < size.z; ++z)
        for (int y = 0; y + 1 < size.y; ++y)
            for (int x = 0; x + 1 < size.x; ++x) {
                const glm::ivec3 cube(x, y, z);
                std::array<double, 8> f{};
                int insideCorners = 0;
                for (int c = 0; c < 8; ++c) {
                    f[static_cast<std::size_t>(c)] = value(cube + glm::ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1));
                    insideCorners += f[static_cast<std::size_t>(c)] >= iso ? 1 : 0;
                }
                if (insideCorners == 0 || insideCorners == 8) continue;
                for (const auto& tet : tets) {
                    std::array<glm::ivec3, 4> in{}, out{};
                    std::size_t ins = 0, outs = 0;
                    for (const glm::ivec3& corner : tet) {
                        const std::size_t c = static_cast<std::size_t>(corner.x + 2 * corner.y + 4 * corner.z);
                        if (f[c] >= iso) in[ins++] = cube + corner;
                        else out[outs++] = cube + corner;
                    }
                    if (ins == 0 || outs == 0) continue;
                    glm::dvec3 inCentre(0.0), outCentre(0.0);
                    for (std::size_t p = 0; p < ins; ++p) inCentre += glm::dvec3(in[p]) / double(ins);
                    for (std::size_t p = 0; p < outs; ++p) outCentre += glm::dvec3(out[p]) / double(outs);
                    const glm::dvec3 direction = outCentre - inCentre;
                    if (ins == 1) {
                        emit({{{in[0], out[0]}, {in[0], out[1]}, {in[0], out[2]}, {}}}, 3, direction);
                    } else if (outs == 1) {
                        emit({{{in[0], out[0]}, {in[1], out[0]}, {in[2], out[0]}, {}}}, 3, direction);
                    } else {
                        // Two in, two out: the crossed edges form a quad in cyclic order a0-b0, a0-b1, a1-b1, a1-b0.
                        emit({{{in[0], out[0]}, {in[0], out[1]}, {in[1], out[1]}, {in[1], out[0]}}}, 4, direction);
                    }
                }
            }
    return mesh;
}

clip::TriangleMesh cavitySurface(const RemovalField& field, const std::vector<std::uint8_t>& tissueInFieldBox) {
    const VoxelBox box = field.box();
    if (!tissueInFieldBox.empty() && tissueInFieldBox.size() != box.voxelCount())
        throw InputError("<cavity surface>", "tissue", "one flag per voxel of the field box", std::to_string(tissueInFieldBox.size()));
    std::vector<double> values(box.voxelCount());
    for (std::size_t i = 0; i < values.size(); ++i) {
        const bool tissue = tissueInFieldBox.empty() || tissueInFieldBox[i];
        values[i] = tissue ? double(field.insideSamples[i]) / double(field.samplesPerVoxel) : 0.0;
    }
    return isoSurfaceTetrahedra(box, values, field.indexToWorld, 0.5);
}

}  // namespace curette::plan
