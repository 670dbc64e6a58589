#include "plan/distance_transform.h"

#include "base/parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace curette::plan {

namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();
}

glm::dvec3 gridSpacingMm(const glm::dmat4& indexToWorld) {
    return {glm::length(glm::dvec3(indexToWorld[0])), glm::length(glm::dvec3(indexToWorld[1])),
            glm::length(glm::dvec3(indexToWorld[2]))};
}

void lowerEnvelopeOfParabolas(double* f, int n, double spacing, std::vector<int>& v, std::vector<double>& z,
                              std::vector<double>& out) {
    // FH 2012, algorithm DT(f) with positions x_q = q * spacing. v: the parabolas of the envelope, z: the
    // boundaries between them.
    v.resize(static_cast<std::size_t>(n));
    z.resize(static_cast<std::size_t>(n) + 1);
    out.resize(static_cast<std::size_t>(n));
    auto at = [](auto& a, int i) -> auto& { return a[static_cast<std::size_t>(i)]; };
    int k = -1;
    for (int q = 0; q < n; ++q) {
        if (f[q] == kInfinity) continue;
        const double xq = q * spacing, hq = f[q] + xq * xq;
        double s = -kInfinity;
        while (k >= 0) {
            const int p = at(v, k);
            const double xp = p * spacing;
            // Where the parabola of q overtakes that of p.
            s = (hq - (f[p] + xp * xp)) / (2.0 * (xq - xp));
            if (s > at(z, k)) break;
            --k;
        }
        ++k;
        at(v, k) = q;
        at(z, k) = k == 0 ? -kInfinity : s;
        at(z, k + 1) = kInfinity;
    }
    if (k < 0) return;  // no parabola: everything stays infinite
    int j = 0;
    for (int q = 0; q < n; ++q) {
        const double x = q * spacing;
        while (at(z, j + 1) < x) ++j;
        const double d = x - at(v, j) * spacing;
        at(out, q) = d * d + f[at(v, j)];
    }
    for (int q = 0; q < n; ++q) f[q] = at(out, q);
}

namespace {

// Scratch for one thread's lines (the lines of one pass are independent: base/parallel.h).
struct LineScratch {
    std::vector<int> v;
    std::vector<double> z, out, line;
};

template <typename Body>
void overLines(std::size_t lines, const Body& body) {
    splitAcrossThreads(lines, [&](std::size_t first, std::size_t end) {
        LineScratch scratch;
        body(first, end, scratch);
    });
}

}  // namespace

std::vector<double> squaredDistanceTransformMm(glm::ivec3 dims, glm::dvec3 spacingMm, const std::vector<std::uint8_t>& isFeature) {
    const std::size_t nx = static_cast<std::size_t>(dims.x), ny = static_cast<std::size_t>(dims.y),
                      nz = static_cast<std::size_t>(dims.z);
    std::vector<double> d(nx * ny * nz, kInfinity);
    for (std::size_t i = 0; i < d.size(); ++i)
        if (isFeature[i]) d[i] = 0.0;

    // Pass along x: rows are contiguous. A row without features stays infinite.
    overLines(ny * nz, [&](std::size_t first, std::size_t end, LineScratch& s) {
        for (std::size_t row = first; row < end; ++row) {
            double* r = d.data() + row * nx;
            bool any = false;
            for (std::size_t i = 0; i < nx && !any; ++i) any = r[i] == 0.0;
            if (any) lowerEnvelopeOfParabolas(r, dims.x, spacingMm.x, s.v, s.z, s.out);
        }
    });
    // Passes along y and z on strided lines, copied into a buffer. A line that is infinite throughout (no
    // feature in its plane so far) is skipped: most of the grid for a small feature set.
    auto strided = [&](std::size_t count, std::size_t stride, double spacing, auto lineStart, std::size_t lines) {
        overLines(lines, [&](std::size_t first, std::size_t end, LineScratch& s) {
            s.line.resize(count);
            for (std::size_t l = first; l < end; ++l) {
                const std::size_t start = lineStart(l);
                bool any = false;
                for (std::size_t q = 0; q < count; ++q) {
                    s.line[q] = d[start + q * stride];
                    any = any || s.line[q] != kInfinity;
                }
                if (!any) continue;
                lowerEnvelopeOfParabolas(s.line.data(), static_cast<int>(count), spacing, s.v, s.z, s.out);
                for (std::size_t q = 0; q < count; ++q) d[start + q * stride] = s.line[q];
            }
        });
    };
    strided(ny, nx, spacingMm.y, [&](std::size_t l) { return (l / nx) * nx * ny + l % nx; }, nx * nz);
    strided(nz, nx * ny, spacingMm.z, [&](std::size_t l) { return l; }, nx * ny);
    return d;
}

std::vector<double> distanceTransformMm(glm::ivec3 dims, glm::dvec3 spacingMm, const std::vector<std::uint8_t>& isFeature) {
    std::vector<double> d = squaredDistanceTransformMm(dims, spacingMm, isFeature);
    for (double& x : d) x = std::sqrt(x);
    return d;
}

}  // namespace curette::plan
