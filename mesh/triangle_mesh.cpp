#include "mesh/triangle_mesh.h"

#include "base/error.h"

#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <unordered_map>

namespace curette::clip {

glm::dvec3 TriangleMesh::boundsMin() const {
    glm::dvec3 m(std::numeric_limits<double>::infinity());
    for (const glm::vec3& p : positions) m = glm::min(m, glm::dvec3(p));
    return m;
}

glm::dvec3 TriangleMesh::boundsMax() const {
    glm::dvec3 m(-std::numeric_limits<double>::infinity());
    for (const glm::vec3& p : positions) m = glm::max(m, glm::dvec3(p));
    return m;
}

double TriangleMesh::signedVolume() const {
    double v = 0;
    for (const glm::uvec3& t : triangles)
        v += glm::dot(glm::dvec3(positions[t.x]), glm::cross(glm::dvec3(positions[t.y]), glm::dvec3(positions[t.z])));
    return v / 6.0;
}

double TriangleMesh::surfaceArea() const {
    double a = 0;
    for (const glm::uvec3& t : triangles) {
        glm::dvec3 p0(positions[t.x]), p1(positions[t.y]), p2(positions[t.z]);
        a += 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
    }
    return a;
}

void weldVertices(TriangleMesh& mesh, double tolerance) {
    if (!(tolerance > 0) || !std::isfinite(tolerance)) throw InputError(mesh.source, "mesh", "a positive welding tolerance");
    for (const glm::vec3& p : mesh.positions)
        if (!(std::abs(p.x) / tolerance < 9e15 && std::abs(p.y) / tolerance < 9e15 && std::abs(p.z) / tolerance < 9e15))
            throw InputError(mesh.source, "mesh", "coordinates within 9e15 welding tolerances of the origin");
    // Grid hashing on cells of size `tolerance`, checking the neighbouring cells.
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
    auto cellOf = [&](glm::dvec3 p) { return glm::i64vec3(glm::floor(p / tolerance)); };
    auto key = [](glm::i64vec3 c) {
        return (static_cast<std::uint64_t>(c.x & 0x1fffff) << 42) | (static_cast<std::uint64_t>(c.y & 0x1fffff) << 21) |
               static_cast<std::uint64_t>(c.z & 0x1fffff);
    };
    std::vector<glm::vec3> welded;
    std::vector<std::uint32_t> remap(mesh.positions.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        glm::dvec3 p(mesh.positions[i]);
        glm::i64vec3 c = cellOf(p);
        std::uint32_t found = std::numeric_limits<std::uint32_t>::max();
        for (int dz = -1; dz <= 1 && found == std::numeric_limits<std::uint32_t>::max(); ++dz)
            for (int dy = -1; dy <= 1 && found == std::numeric_limits<std::uint32_t>::max(); ++dy)
                for (int dx = -1; dx <= 1 && found == std::numeric_limits<std::uint32_t>::max(); ++dx) {
                    auto it = cells.find(key(c + glm::i64vec3(dx, dy, dz)));
                    if (it == cells.end()) continue;
                    for (std::uint32_t w : it->second)
                        if (glm::distance(glm::dvec3(welded[w]), p) <= tolerance) {
                            found = w;
                            break;
                        }
                }
        if (found == std::numeric_limits<std::uint32_t>::max()) {
            found = static_cast<std::uint32_t>(welded.size());
            welded.push_back(mesh.positions[i]);
            cells[key(c)].push_back(found);
        }
        remap[i] = found;
    }
    std::vector<glm::uvec3> triangles;
    for (const glm::uvec3& t : mesh.triangles) {
        glm::uvec3 r(remap[t.x], remap[t.y], remap[t.z]);
        if (r.x != r.y && r.y != r.z && r.x != r.z) triangles.push_back(r);
    }
    mesh.positions = std::move(welded);
    mesh.triangles = std::move(triangles);
}

void validateClosed(const TriangleMesh& mesh) {
    if (mesh.triangles.empty()) throw InputError(mesh.source, "mesh", "a closed surface of triangles", "no triangles");
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (const glm::uvec3& t : mesh.triangles) {
        for (std::uint32_t i : {t.x, t.y, t.z})
            if (i >= mesh.positions.size())
                throw InputError(mesh.source, "mesh", "triangle indices below the vertex count", std::to_string(i));
        for (int e = 0; e < 3; ++e) ++directed[{t[e], t[(e + 1) % 3]}];
    }
    std::size_t boundary = 0, nonManifold = 0, flipped = 0;
    std::pair<std::uint32_t, std::uint32_t> example{0, 0};
    for (const auto& [edge, count] : directed) {
        auto reverse = directed.find({edge.second, edge.first});
        int opposite = reverse == directed.end() ? 0 : reverse->second;
        if (count > 1) {
            // The same directed edge twice: either more than two triangles meet here or two neighbours
            // disagree on orientation.
            (opposite + count > 2 ? nonManifold : flipped)++;
            example = edge;
        } else if (opposite == 0) {
            ++boundary;
            example = edge;
        }
    }
    auto where = [&] { return "between vertices " + std::to_string(example.first) + " and " + std::to_string(example.second); };
    if (boundary)
        throw InputError(mesh.source, "mesh", "a closed surface (every edge shared by exactly two triangles)",
                         std::to_string(boundary) + " boundary edges, e.g. " + where());
    if (nonManifold)
        throw InputError(mesh.source, "mesh", "a 2-manifold surface (two triangles per edge)",
                         std::to_string(nonManifold) + " edges with more than two triangles, e.g. " + where());
    if (flipped)
        throw InputError(mesh.source, "mesh", "consistently oriented triangles",
                         std::to_string(flipped) + " edges where neighbours disagree, e.g. " + where());
}

void orientOutward(TriangleMesh& mesh) {
    if (mesh.signedVolume() >= 0) return;
    for (glm::uvec3& t : mesh.triangles) std::swap(t.y, t.z);
}

bool containsPoint(const TriangleMesh& mesh, glm::dvec3 p) {
    double total = 0;
    for (const glm::uvec3& t : mesh.triangles) {
        glm::dvec3 a = glm::dvec3(mesh.positions[t.x]) - p, b = glm::dvec3(mesh.positions[t.y]) - p,
                   c = glm::dvec3(mesh.positions[t.z]) - p;
        double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
        double numerator = glm::dot(a, glm::cross(b, c));
        double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
        total += 2.0 * std::atan2(numerator, denominator);  // the triangle's signed solid angle
    }
    return total / (4.0 * std::numbers::pi) > 0.5;
}

}  // namespace curette::clip
