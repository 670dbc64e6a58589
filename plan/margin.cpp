#include "plan/margin.h"

#include "mesh/coverage.h"
#include "plan/distance_transform.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace curette::plan {

namespace {

std::size_t linear(glm::ivec3 v, glm::ivec3 dims) {
    return (static_cast<std::size_t>(v.z) * static_cast<std::size_t>(dims.y) + static_cast<std::size_t>(v.y)) *
               static_cast<std::size_t>(dims.x) + static_cast<std::size_t>(v.x);
}

}  // namespace

CellGaps cellGapsTo(glm::ivec3 dims, const glm::dmat4& indexToWorld, const std::vector<Touch>& touch) {
    CellGaps gaps;
    gaps.dims = dims;
    gaps.spacingMm = gridSpacingMm(indexToWorld);
    gaps.worldToIndex = glm::inverse(indexToWorld);
    gaps.indexToWorld = indexToWorld;
    if (std::all_of(touch.begin(), touch.end(), [](Touch t) { return t == Touch::None; })) return gaps;
    // Corner c of the lattice is the corner at index position c - 0.5: cell v has corners v .. v + 1.
    const glm::ivec3 corners = dims + 1;
    std::vector<std::uint8_t> removedCorner(linear(corners - 1, corners) + 1, 0);
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i) {
                if (touch[linear({i, j, k}, dims)] == Touch::None) continue;
                for (int c = 0; c < 8; ++c)
                    removedCorner[linear(glm::ivec3(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1)), corners)] = 1;
            }
    gaps.cornerDistance2 = squaredDistanceTransformMm(corners, gaps.spacingMm, removedCorner);
    // A cell's gap is its nearest corner's: a 2 x 2 x 2 minimum, one axis at a time.
    std::vector<double> minX(static_cast<std::size_t>(dims.x) * corners.y * corners.z), minXY(static_cast<std::size_t>(dims.x) * dims.y * corners.z);
    for (int k = 0; k < corners.z; ++k)
        for (int j = 0; j < corners.y; ++j)
            for (int i = 0; i < dims.x; ++i)
                minX[linear({i, j, k}, {dims.x, corners.y, corners.z})] =
                    std::min(gaps.cornerDistance2[linear({i, j, k}, corners)], gaps.cornerDistance2[linear({i + 1, j, k}, corners)]);
    for (int k = 0; k < corners.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i)
                minXY[linear({i, j, k}, {dims.x, dims.y, corners.z})] =
                    std::min(minX[linear({i, j, k}, {dims.x, corners.y, corners.z})], minX[linear({i, j + 1, k}, {dims.x, corners.y, corners.z})]);
    gaps.cellGap2.resize(linear(dims - 1, dims) + 1);
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i)
                gaps.cellGap2[linear({i, j, k}, dims)] =
                    std::min(minXY[linear({i, j, k}, {dims.x, dims.y, corners.z})], minXY[linear({i, j, k + 1}, {dims.x, dims.y, corners.z})]);
    return gaps;
}

double CellGaps::distanceMm(glm::dvec3 world) const {
    if (empty()) return std::numeric_limits<double>::infinity();
    const glm::ivec3 corners = dims + 1;
    // Corner-lattice coordinates: the index of the voxel centre plus a half. Points beyond the lattice take
    // its border's values, which are never larger than theirs.
    glm::dvec3 q = glm::dvec3(worldToIndex * glm::dvec4(world, 1.0)) + 0.5;
    q = glm::clamp(q, glm::dvec3(0.0), glm::dvec3(corners - 1));
    const glm::ivec3 base = glm::min(glm::ivec3(glm::floor(q)), corners - 2);
    const glm::dvec3 w = q - glm::dvec3(base);
    double sum = 0;
    for (int c = 0; c < 8; ++c) {
        const glm::ivec3 o(c & 1, (c >> 1) & 1, (c >> 2) & 1);
        const double weight = (o.x ? w.x : 1 - w.x) * (o.y ? w.y : 1 - w.y) * (o.z ? w.z : 1 - w.z);
        if (weight > 0) sum += weight * std::sqrt(cornerDistance2[linear(base + o, corners)]);
    }
    return sum;
}

CellGaps::Bounds CellGaps::distanceBoundsMm(glm::dvec3 world) const {
    const double infinity = std::numeric_limits<double>::infinity();
    if (empty()) return {infinity, infinity};
    const glm::ivec3 corners = dims + 1;
    glm::dvec3 q = glm::clamp(glm::dvec3(worldToIndex * glm::dvec4(world, 1.0)) + 0.5, glm::dvec3(0.0), glm::dvec3(corners - 1));
    const glm::ivec3 base = glm::min(glm::ivec3(glm::floor(q)), corners - 2);
    Bounds b{0, infinity};
    for (int c = 0; c < 8; ++c) {
        const glm::ivec3 corner = base + glm::ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
        const double d = std::sqrt(cornerDistance2[linear(corner, corners)]);
        // Corner c of the lattice is the cell corner at index position c - 0.5.
        const double away = glm::length(glm::dvec3(indexToWorld * glm::dvec4(glm::dvec3(corner) - 0.5, 1.0)) - world);
        b.lower = std::max(b.lower, d - away);
        b.upper = std::min(b.upper, d + away);
    }
    return b;
}

double marginUncertaintyMm(glm::dvec3 spacingMm) { return glm::length(spacingMm); }

namespace {

// Distances in mm from the corners of a box of cells to the nearest corner of a structure's cells (exact for
// the corners of the box when every structure cell lies in it: the separable transform's lines then meet
// every feature).
struct CornerDistances {
    glm::ivec3 origin{0}, size{0};   // corners origin .. origin + size - 1 (corner c: index position c - 0.5)
    std::vector<double> mm;

    double at(glm::ivec3 corner) const { return mm[linear(corner - origin, size)]; }
    double cellLower(glm::ivec3 v) const {
        double best = std::numeric_limits<double>::infinity();
        for (int c = 0; c < 8; ++c) best = std::min(best, at(v + glm::ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1)));
        return best;
    }
    // Trilinear at an index position inside the box.
    double trilinear(glm::dvec3 index) const {
        const glm::dvec3 q = index + 0.5 - glm::dvec3(origin);
        const glm::ivec3 base = glm::clamp(glm::ivec3(glm::floor(q)), glm::ivec3(0), size - 2);
        const glm::dvec3 w = glm::clamp(q - glm::dvec3(base), 0.0, 1.0);
        double sum = 0;
        for (int c = 0; c < 8; ++c) {
            const glm::ivec3 o(c & 1, (c >> 1) & 1, (c >> 2) & 1);
            const double weight = (o.x ? w.x : 1 - w.x) * (o.y ? w.y : 1 - w.y) * (o.z ? w.z : 1 - w.z);
            if (weight > 0) sum += weight * mm[linear(base + o, size)];
        }
        return sum;
    }
};

}  // namespace

namespace {

// How far a structure is: a lower bound over a whole cell, the distance from a point, and whether a point lies
// in it (contact), all in the grid's index coordinates.
struct StructureDistance {
    std::function<double(glm::ivec3 cell)> cellLower;
    std::function<double(glm::dvec3 index)> at;
    std::function<bool(glm::dvec3 index)> contains;
};

// The gap from what the carve removes to a structure: whole cells by their lower bound (exact for cell
// structures), cells covered in part and the untouched ring around the touched ones by probing (their own
// clip samples, a sub-point lattice, then a ray from the nearest inside point down the distance), nearest
// first, in batches, until no cell can lower the margin. Candidates lie in [lo, hi].
// With `exactCells` a whole cell's lower bound is its gap (a structure of cells); without, whole cells on the
// boundary are probed too.
Margin refineOver(glm::ivec3 dims, const glm::dmat4& indexToWorld, glm::ivec3 lo, glm::ivec3 hi, const std::vector<Touch>& touch,
                  const StructureDistance& structure, bool exactCells, const std::vector<glm::dvec3>& sampleOffsets,
                  const PointsInside& inside) {
    Margin margin;
    margin.mm = std::numeric_limits<double>::infinity();
    const glm::dvec3 spacing = gridSpacingMm(indexToWorld);
    struct Candidate {
        double lower;
        glm::ivec3 cell;
        bool touched;
    };
    std::vector<Candidate> candidates;
    auto touchAt = [&](glm::ivec3 v) { return touch[linear(v, dims)]; };
    auto inGrid = [&](glm::ivec3 v) { return glm::all(glm::greaterThanEqual(v, glm::ivec3(0))) && glm::all(glm::lessThan(v, dims)); };
    for (int k = lo.z; k <= hi.z; ++k)
        for (int j = lo.y; j <= hi.y; ++j)
            for (int i = lo.x; i <= hi.x; ++i) {
                const glm::ivec3 v(i, j, k);
                const Touch t = touchAt(v);
                // Only cells on the touched region's boundary can hold its nearest point.
                bool boundary = false, ring = false;
                for (int n = 0; n < 27 && !(boundary && ring); ++n) {
                    const glm::ivec3 w = v + glm::ivec3(n % 3 - 1, n / 3 % 3 - 1, n / 9 - 1);
                    const bool touched = inGrid(w) && touchAt(w) != Touch::None;
                    boundary = boundary || !touched;
                    ring = ring || touched;
                }
                if (t == Touch::Whole && exactCells) {
                    if (boundary) margin.mm = std::min(margin.mm, structure.cellLower(v));
                } else if ((t == Touch::Whole && boundary) || t == Touch::Part || (t == Touch::None && ring)) {
                    candidates.push_back({structure.cellLower(v), v, t != Touch::None});
                }
            }
    std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) { return a.lower < b.lower; });
    if (!inside) {
        for (const Candidate& c : candidates)
            if (c.touched) margin.mm = std::min(margin.mm, c.lower);
        margin.uncertaintyMm = marginUncertaintyMm(spacing);
        return margin;
    }
    const glm::ivec3 perAxis = glm::clamp(glm::ivec3(glm::ceil(spacing / kRefineStepMm)), glm::ivec3(2), glm::ivec3(8));
    const glm::dvec3 subStep = 1.0 / glm::dvec3(perAxis);   // index units
    const double subDiagonalMm = glm::length(subStep * spacing);
    constexpr int kRaySteps = 16;
    std::vector<glm::dvec3> cellPoints;                       // index offsets from a cell's centre
    cellPoints.emplace_back(0.0);
    for (int c = 0; c < 8; ++c) {
        const double h = clip::kCellSampleHalfWidth;
        cellPoints.emplace_back((c & 1) ? h : -h, (c & 2) ? h : -h, (c & 4) ? h : -h);
    }
    cellPoints.insert(cellPoints.end(), sampleOffsets.begin(), sampleOffsets.end());
    for (int c = 0; c < perAxis.z; ++c)
        for (int b = 0; b < perAxis.y; ++b)
            for (int a = 0; a < perAxis.x; ++a) cellPoints.push_back((glm::dvec3(a, b, c) + 0.5) * subStep - 0.5);
    const std::size_t perCell = cellPoints.size();
    auto toWorld = [&](glm::dvec3 index) { return glm::dvec3(indexToWorld * glm::dvec4(index, 1.0)); };

    std::vector<glm::dvec3> points, indices;
    for (std::size_t first = 0; first < candidates.size() && candidates[first].lower < margin.mm;) {
        std::size_t end = first;
        points.clear(), indices.clear();
        while (end < candidates.size() && candidates[end].lower < margin.mm && points.size() + perCell <= (1u << 20)) {
            for (const glm::dvec3& o : cellPoints) {
                indices.push_back(glm::dvec3(candidates[end].cell) + o);
                points.push_back(toWorld(indices.back()));
            }
            ++end;
        }
        const std::vector<std::uint8_t> flags = inside(points);
        // The nearest inside point of each cell, then the ray from it.
        std::vector<glm::dvec3> rayIndices, rayPoints;
        std::vector<double> best(end - first, std::numeric_limits<double>::infinity());
        for (std::size_t cell = first; cell < end; ++cell) {
            glm::dvec3 nearest(0.0);
            for (std::size_t p = (cell - first) * perCell; p < (cell - first + 1) * perCell; ++p) {
                if (!flags[p]) continue;
                if (structure.contains(indices[p])) margin.contact = true;
                const double dp = structure.at(indices[p]);
                if (dp < best[cell - first]) best[cell - first] = dp, nearest = indices[p];
            }
            // Down the distance's gradient (in index units: the world gradient over the spacing, squared).
            glm::dvec3 direction(0.0);
            if (std::isfinite(best[cell - first]))
                for (int a = 0; a < 3; ++a) {
                    glm::dvec3 e(0.0);
                    e[a] = 0.05;
                    direction[a] = -(structure.at(nearest + e) - structure.at(nearest - e)) / (0.1 * spacing[a] * spacing[a]);
                }
            const double worldLength = glm::length(direction * spacing);
            for (int step = 1; step <= kRaySteps; ++step) {
                const glm::dvec3 index = worldLength > 0 ? nearest + direction * (subDiagonalMm * step / kRaySteps / worldLength) : nearest;
                rayIndices.push_back(index);
                rayPoints.push_back(toWorld(index));
            }
        }
        const std::vector<std::uint8_t> rayFlags = inside(rayPoints);
        for (std::size_t cell = first; cell < end; ++cell) {
            double& b = best[cell - first];
            if (std::isfinite(b))
                for (std::size_t p = (cell - first) * kRaySteps; p < (cell - first + 1) * kRaySteps; ++p) {
                    if (!rayFlags[p]) break;
                    if (structure.contains(rayIndices[p])) margin.contact = true;
                    b = std::min(b, structure.at(rayIndices[p]));
                }
            // A touched cell none of whose points answers inside (the clip test disagrees with the field):
            // keep its lower bound, never larger than its part's gap.
            if (!std::isfinite(b) && candidates[cell].touched) b = candidates[cell].lower;
            margin.mm = std::min(margin.mm, std::max(b, candidates[cell].lower));
        }
        first = end;
    }
    if (margin.contact) margin.mm = 0;
    margin.uncertaintyMm = subDiagonalMm / 4;
    return margin;
}

// The bounding box of the touched cells grown by one (their ring), clamped to the grid; hi.x < 0 when none.
void touchedBox(glm::ivec3 dims, const std::vector<Touch>& touch, glm::ivec3& lo, glm::ivec3& hi) {
    lo = glm::ivec3(std::numeric_limits<int>::max()), hi = glm::ivec3(-1);
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i)
                if (touch[linear({i, j, k}, dims)] != Touch::None)
                    lo = glm::min(lo, glm::ivec3(i, j, k)), hi = glm::max(hi, glm::ivec3(i, j, k));
    if (hi.x < 0) return;
    lo = glm::max(lo - 1, glm::ivec3(0)), hi = glm::min(hi + 1, dims - 1);
}

}  // namespace

Margin refinedMargin(glm::ivec3 dims, const glm::dmat4& indexToWorld, const std::vector<Touch>& touch,
                     const std::vector<std::uint8_t>& inStructure, const std::vector<glm::dvec3>& sampleOffsets,
                     const PointsInside& inside) {
    glm::ivec3 lo, hi;
    touchedBox(dims, touch, lo, hi);
    Margin none;
    none.mm = std::numeric_limits<double>::infinity();
    if (hi.x < 0) return none;
    // The corner distances over the box of the touched cells and the structure's, exact there.
    glm::ivec3 boxLo = lo, boxHi = hi;
    bool anyStructure = false;
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i)
                if (inStructure[linear({i, j, k}, dims)])
                    anyStructure = true, boxLo = glm::min(boxLo, glm::ivec3(i, j, k)), boxHi = glm::max(boxHi, glm::ivec3(i, j, k));
    if (!anyStructure) return none;
    CornerDistances d;
    d.origin = boxLo;
    d.size = boxHi - boxLo + 2;
    std::vector<std::uint8_t> structureCorner(linear(d.size - 1, d.size) + 1, 0);
    for (int k = boxLo.z; k <= boxHi.z; ++k)
        for (int j = boxLo.y; j <= boxHi.y; ++j)
            for (int i = boxLo.x; i <= boxHi.x; ++i)
                if (inStructure[linear({i, j, k}, dims)])
                    for (int c = 0; c < 8; ++c)
                        structureCorner[linear(glm::ivec3(i, j, k) - boxLo + glm::ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1), d.size)] = 1;
    d.mm = squaredDistanceTransformMm(d.size, gridSpacingMm(indexToWorld), structureCorner);
    for (double& x : d.mm) x = std::sqrt(x);
    StructureDistance distance;
    distance.cellLower = [&](glm::ivec3 v) { return d.cellLower(v); };
    distance.at = [&](glm::dvec3 index) { return d.trilinear(index); };
    distance.contains = [&](glm::dvec3 index) {
        const glm::ivec3 v = glm::clamp(glm::ivec3(glm::floor(index + 0.5)), glm::ivec3(0), dims - 1);
        return inStructure[linear(v, dims)] != 0;
    };
    return refineOver(dims, indexToWorld, lo, hi, touch, distance, true, sampleOffsets, inside);
}

Margin refinedMarginToPoints(glm::ivec3 dims, const glm::dmat4& indexToWorld, const std::vector<Touch>& touch,
                             const std::vector<glm::dvec3>& points, double reachMm, const std::vector<glm::dvec3>& sampleOffsets,
                             const PointsInside& inside) {
    glm::ivec3 lo, hi;
    touchedBox(dims, touch, lo, hi);
    Margin none;
    none.mm = std::numeric_limits<double>::infinity();
    if (hi.x < 0 || points.empty()) return none;
    {
        // Only cells within reach of the points can hold the nearest approach.
        const glm::dmat4 toIndex = glm::inverse(indexToWorld);
        glm::dvec3 a(std::numeric_limits<double>::infinity()), b(-std::numeric_limits<double>::infinity());
        for (const glm::dvec3& p : points) {
            const glm::dvec3 q(toIndex * glm::dvec4(p, 1.0));
            a = glm::min(a, q), b = glm::max(b, q);
        }
        const glm::dvec3 grow = reachMm / gridSpacingMm(indexToWorld) + 1.0;
        lo = glm::max(lo, glm::ivec3(glm::floor(a - grow))), hi = glm::min(hi, glm::ivec3(glm::ceil(b + grow)));
        if (glm::any(glm::lessThan(hi, lo))) return none;
    }
    // The points hashed into buckets of about 4 mm in index space; a query searches shells of buckets
    // outwards until no unsearched bucket can hold a nearer point.
    const glm::dvec3 spacing = gridSpacingMm(indexToWorld);
    const glm::dmat4 worldToIndex = glm::inverse(indexToWorld);
    const glm::dvec3 bucket = glm::max(glm::dvec3(4.0) / spacing, glm::dvec3(1.0));   // index units
    std::vector<glm::dvec3> indexPoints(points.size());
    glm::dvec3 pmin(std::numeric_limits<double>::infinity()), pmax(-std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < points.size(); ++i) {
        indexPoints[i] = glm::dvec3(worldToIndex * glm::dvec4(points[i], 1.0));
        pmin = glm::min(pmin, indexPoints[i]), pmax = glm::max(pmax, indexPoints[i]);
    }
    const glm::ivec3 buckets = glm::clamp(glm::ivec3(glm::floor((pmax - pmin) / bucket)) + 1, glm::ivec3(1), glm::ivec3(512));
    std::vector<std::vector<std::uint32_t>> grid(static_cast<std::size_t>(buckets.x) * buckets.y * buckets.z);
    auto bucketOf = [&](glm::dvec3 index) { return glm::clamp(glm::ivec3(glm::floor((index - pmin) / bucket)), glm::ivec3(0), buckets - 1); };
    for (std::size_t i = 0; i < indexPoints.size(); ++i) grid[linear(bucketOf(indexPoints[i]), buckets)].push_back(static_cast<std::uint32_t>(i));
    const glm::dvec3 bucketSizeMm = bucket * spacing;
    const double bucketMm = std::min({bucketSizeMm.x, bucketSizeMm.y, bucketSizeMm.z});
    // The distance in mm from an index point to the nearest point (orthogonal grids: the column norms are the
    // spacings).
    auto nearest = [&](glm::dvec3 index) {
        const glm::ivec3 home = bucketOf(index);
        double best2 = std::numeric_limits<double>::infinity();
        for (int shell = 0;; ++shell) {
            const glm::ivec3 a = glm::max(home - shell, glm::ivec3(0)), b = glm::min(home + shell, buckets - 1);
            for (int z = a.z; z <= b.z; ++z)
                for (int y = a.y; y <= b.y; ++y)
                    for (int x = a.x; x <= b.x; ++x) {
                        const glm::ivec3 off = glm::abs(glm::ivec3(x, y, z) - home);
                        if (std::max({off.x, off.y, off.z}) != shell) continue;
                        for (std::uint32_t i : grid[linear({x, y, z}, buckets)]) {
                            const glm::dvec3 d = (indexPoints[i] - index) * spacing;
                            best2 = std::min(best2, glm::dot(d, d));
                        }
                    }
            // Every point beyond this shell lies at least `shell` buckets away from the query's bucket.
            const bool covered = glm::all(glm::lessThanEqual(home - shell, glm::ivec3(0))) && glm::all(glm::greaterThanEqual(home + shell, buckets - 1));
            if (covered || (std::isfinite(best2) && std::sqrt(best2) <= shell * bucketMm)) return std::sqrt(best2);
        }
    };
    const double halfDiagonal = 0.5 * glm::length(spacing);
    StructureDistance distance;
    distance.cellLower = [&](glm::ivec3 v) { return std::max(nearest(glm::dvec3(v)) - halfDiagonal, 0.0); };
    distance.at = nearest;
    distance.contains = [](glm::dvec3) { return false; };   // a streamline has no volume: its cut is the probe's
    return refineOver(dims, indexToWorld, lo, hi, touch, distance, false, sampleOffsets, inside);
}

}  // namespace curette::plan
