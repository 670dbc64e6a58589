#include "io/slice_contours.h"

#include <array>

namespace curette::io {

namespace {

// A boundary edge between corner lattice points (x, y) (pixel (i, j) spans corners (i, j) .. (i + 1, j + 1)),
// directed so that the set pixel is on its left.
struct Edge {
    int x0, y0, x1, y1;
    bool used = false;
};

}  // namespace

std::vector<std::vector<glm::dvec2>> sliceOutlines(const std::uint8_t* mask, int width, int height) {
    auto set = [&](int i, int j) { return i >= 0 && j >= 0 && i < width && j < height && mask[std::size_t(j) * width + i] != 0; };
    std::vector<Edge> edges;
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i) {
            if (!set(i, j)) continue;
            if (!set(i, j - 1)) edges.push_back({i, j, i + 1, j});
            if (!set(i + 1, j)) edges.push_back({i + 1, j, i + 1, j + 1});
            if (!set(i, j + 1)) edges.push_back({i + 1, j + 1, i, j + 1});
            if (!set(i - 1, j)) edges.push_back({i, j + 1, i, j});
        }
    // Outgoing edges by start corner: at most two (a corner where set pixels meet diagonally).
    const std::size_t corners = std::size_t(width + 1) * std::size_t(height + 1);
    std::vector<std::array<int, 2>> outgoing(corners, {-1, -1});
    auto corner = [&](int x, int y) { return std::size_t(y) * std::size_t(width + 1) + std::size_t(x); };
    for (int e = 0; e < int(edges.size()); ++e) {
        auto& slot = outgoing[corner(edges[e].x0, edges[e].y0)];
        slot[slot[0] < 0 ? 0 : 1] = e;
    }
    std::vector<std::vector<glm::dvec2>> polygons;
    for (int first = 0; first < int(edges.size()); ++first) {
        if (edges[first].used) continue;
        std::vector<glm::ivec2> path;
        int e = first;
        while (!edges[e].used) {
            Edge& edge = edges[e];
            edge.used = true;
            path.push_back({edge.x0, edge.y0});
            const auto& next = outgoing[corner(edge.x1, edge.y1)];
            int chosen = next[0];
            if (next[1] >= 0) {
                // Two ways on: take the left turn (towards the set pixels), cross product of the directions > 0.
                glm::ivec2 in{edge.x1 - edge.x0, edge.y1 - edge.y0};
                const Edge& a = edges[next[0]];
                glm::ivec2 out{a.x1 - a.x0, a.y1 - a.y0};
                chosen = in.x * out.y - in.y * out.x > 0 ? next[0] : next[1];
                if (edges[chosen].used) chosen = chosen == next[0] ? next[1] : next[0];
            }
            e = chosen;
        }
        // Keep the corners only: drop vertices where the direction does not change.
        std::vector<glm::dvec2> polygon;
        const std::size_t n = path.size();
        for (std::size_t v = 0; v < n; ++v) {
            glm::ivec2 before = path[v] - path[(v + n - 1) % n], after = path[(v + 1) % n] - path[v];
            if (before.x * after.y - before.y * after.x != 0) polygon.push_back(glm::dvec2(path[v]) - glm::dvec2(0.5));
        }
        polygons.push_back(std::move(polygon));
    }
    return polygons;
}

double polygonArea(const std::vector<glm::dvec2>& polygon) {
    double twice = 0.0;
    for (std::size_t v = 0; v < polygon.size(); ++v) {
        const glm::dvec2& a = polygon[v];
        const glm::dvec2& b = polygon[(v + 1) % polygon.size()];
        twice += a.x * b.y - b.x * a.y;
    }
    return 0.5 * twice;
}

}  // namespace curette::io
