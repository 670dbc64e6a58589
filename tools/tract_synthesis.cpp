#include "tools/tract_synthesis.h"

#include "base/error.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace curette {

namespace {

// SplitMix64 (Steele, Lea and Flood 2014): a counter-based generator whose every output is a full 64-bit
// mix of the state, good enough for jitter and defined bit for bit.
struct SplitMix64 {
    std::uint64_t state;
    std::uint64_t next() {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }   // [0, 1), 53 random bits
    // A uniformly distributed point in the unit ball (rejection from the cube).
    glm::dvec3 inBall() {
        for (;;) {
            glm::dvec3 p(2 * uniform() - 1, 2 * uniform() - 1, 2 * uniform() - 1);
            if (glm::dot(p, p) <= 1.0) return p;
        }
    }
};

struct Displacement {
    glm::dvec3 a, b, c;
    double phi, psi;
};

Displacement displacementOf(std::uint64_t seed, std::size_t copy) {
    // The copy's own stream: the seed and the copy index mixed, so streams of neighbouring copies are unrelated.
    SplitMix64 mix{seed};
    SplitMix64 random{mix.next() ^ (static_cast<std::uint64_t>(copy) * 0xD1B54A32D192ED03ull)};
    random.next();
    Displacement d;
    d.a = random.inBall();
    d.b = random.inBall();
    d.c = random.inBall();
    d.phi = 2 * std::numbers::pi * random.uniform();
    d.psi = 2 * std::numbers::pi * random.uniform();
    return d;
}

glm::dvec3 evaluate(const Displacement& d, double jitterMm, double u) {
    return jitterMm * (0.5 * d.a + 0.3 * std::cos(std::numbers::pi * u + d.phi) * d.b + 0.2 * std::cos(2 * std::numbers::pi * u + d.psi) * d.c);
}

}  // namespace

glm::dvec3 synthesisDisplacement(std::uint64_t seed, std::size_t copy, double jitterMm, double u) {
    return evaluate(displacementOf(seed, copy), jitterMm, u);
}

Tractogram synthesiseTracts(const std::vector<Tractogram>& sources, const TractSynthesisSettings& settings) {
    if (!(settings.jitterMm >= 0) || !std::isfinite(settings.jitterMm))
        throw InputError("<tract synthesis>", "jitter", "a jitter bound >= 0 mm", std::to_string(settings.jitterMm));
    if (settings.count == 0 || settings.count > 50'000'000)
        throw InputError("<tract synthesis>", "count", "a streamline count in [1, 50000000]", std::to_string(settings.count));
    // The source streamlines that have points, in order, with the arc-length fraction of every point.
    struct Source {
        const Tractogram* tracts;
        std::size_t s;
    };
    std::vector<Source> list;
    std::string names;
    for (const Tractogram& t : sources) {
        names += (names.empty() ? "" : ", ") + t.source;
        for (std::size_t s = 0; s < t.streamlineCount(); ++s)
            if (t.pointCount(s) > 0) list.push_back({&t, s});
    }
    if (list.empty()) throw InputError(names.empty() ? "<tract synthesis>" : names, "streamlines", "at least one streamline with points", "none");
    std::size_t totalPoints = 0;
    for (std::size_t i = 0; i < settings.count; ++i) totalPoints += list[i % list.size()].tracts->pointCount(list[i % list.size()].s);
    if (totalPoints > 0xFFFFFFFFull)
        throw InputError("<tract synthesis>", "count", "at most 2^32 points in all (fewer copies)", std::to_string(totalPoints) + " points");

    Tractogram out;
    out.source = "synthesised from " + names;
    out.points.reserve(totalPoints);
    out.offsets.reserve(settings.count + 1);
    std::vector<double> fraction;
    for (std::size_t copy = 0; copy < settings.count; ++copy) {
        const Source& from = list[copy % list.size()];
        const Tractogram& t = *from.tracts;
        std::uint32_t first = t.offsets[from.s], n = static_cast<std::uint32_t>(t.pointCount(from.s));
        // Arc-length fraction of every point (a streamline of coincident points takes the index fraction).
        fraction.assign(n, 0.0);
        for (std::uint32_t k = 1; k < n; ++k) fraction[k] = fraction[k - 1] + glm::distance(glm::dvec3(t.points[first + k]), glm::dvec3(t.points[first + k - 1]));
        double length = n > 1 ? fraction[n - 1] : 0.0;
        for (std::uint32_t k = 0; k < n; ++k) fraction[k] = length > 0 ? fraction[k] / length : (n > 1 ? double(k) / (n - 1) : 0.0);
        Displacement d = displacementOf(settings.seed, copy);
        for (std::uint32_t k = 0; k < n; ++k)
            out.points.emplace_back(glm::vec3(glm::dvec3(t.points[first + k]) + evaluate(d, settings.jitterMm, fraction[k])));
        out.offsets.push_back(static_cast<std::uint32_t>(out.points.size()));
    }
    return out;
}

std::vector<std::filesystem::path> tractFilesUnder(const std::filesystem::path& path) {
    namespace fs = std::filesystem;
    if (!fs::exists(path)) throw InputError(path.string(), "--from", "an existing tract file or folder of them", "a path that does not exist");
    if (!fs::is_directory(path)) return {path};
    auto isTract = [](const fs::path& p) {
        std::string name = p.filename().string();
        for (const char* suffix : {".trk", ".tck", ".trx", ".trk.gz", ".tck.gz"}) {
            std::string s(suffix);
            if (name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0) return true;
        }
        return false;
    };
    std::vector<fs::path> files;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(path))
        if (e.is_regular_file() && isTract(e.path())) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    if (files.empty()) throw InputError(path.string(), "--from", "a folder holding .trk, .tck or .trx files", "none in it");
    return files;
}

}  // namespace curette
