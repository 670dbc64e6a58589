#include "render/model/lao_directions.h"

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <random>

namespace curette {

namespace {

std::vector<glm::dvec3> neighbourhood(int manhattanMask) {
    // manhattanMask bit m set: include neighbours with Manhattan distance m (1, 2 or 3).
    std::vector<glm::dvec3> list;
    for (int z = -1; z <= 1; ++z)
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x) {
                int manhattan = std::abs(x) + std::abs(y) + std::abs(z);
                if (manhattan > 0 && (manhattanMask & (1 << manhattan))) list.push_back(glm::normalize(glm::dvec3(x, y, z)));
            }
    return list;
}

std::vector<glm::dvec3> rubik54() {
    std::vector<glm::dvec3> list;
    for (int axis = 0; axis < 3; ++axis)
        for (int side : {-1, 1})
            for (int a = -1; a <= 1; ++a)
                for (int b = -1; b <= 1; ++b) {
                    glm::dvec3 p(0);
                    p[axis] = 1.5 * side;
                    p[(axis + 1) % 3] = a;
                    p[(axis + 2) % 3] = b;
                    list.push_back(glm::normalize(p));
                }
    return list;
}

// Spherical Fibonacci lattice (Keinert et al. 2015, the paper's [18]): z_i = 1 - (2i + 1)/K, azimuth advancing
// by the golden angle.
std::vector<glm::dvec3> fibonacci(int count) {
    std::vector<glm::dvec3> list;
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < count; ++i) {
        double z = 1.0 - (2.0 * i + 1.0) / count;
        double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        double phi = golden * i;
        list.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
    }
    return list;
}

}  // namespace

std::vector<LaoDirection> LaoDirectionSet::build() const {
    std::vector<glm::dvec3> base;
    switch (pattern) {
        case LaoPattern::Neighbourhood6: base = neighbourhood(1 << 1); break;
        case LaoPattern::Neighbourhood14: base = neighbourhood((1 << 1) | (1 << 3)); break;
        case LaoPattern::Neighbourhood26: base = neighbourhood((1 << 1) | (1 << 2) | (1 << 3)); break;
        case LaoPattern::Rubik54: base = rubik54(); break;
        case LaoPattern::Fibonacci: base = fibonacci(std::max(count, 1)); break;
    }
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    std::vector<LaoDirection> list;
    double weightSum = 0;
    for (glm::dvec3 d : base) {
        if (jitter > 0) d = glm::normalize(d + jitter * glm::dvec3(uniform(random), uniform(random), uniform(random)));
        double w = skyWeighting ? 0.5 + 0.5 * d.z : 1.0;
        list.push_back({d, w});
        weightSum += w;
    }
    for (LaoDirection& d : list) d.weight *= static_cast<double>(list.size()) / weightSum;
    return list;
}

std::string LaoDirectionSet::describe() const {
    const char* name = pattern == LaoPattern::Fibonacci ? "Fibonacci" : pattern == LaoPattern::Rubik54 ? "Rubik" : "neighbourhood";
    char text[96];
    std::snprintf(text, sizeof text, "%zu (%s, jitter %g%s)", build().size(), name, jitter, skyWeighting ? ", sky weights" : "");
    return text;
}

bool parseLaoPattern(const std::string& text, LaoDirectionSet& out) {
    if (text == "6") out.pattern = LaoPattern::Neighbourhood6, out.count = 6;
    else if (text == "14") out.pattern = LaoPattern::Neighbourhood14, out.count = 14;
    else if (text == "26") out.pattern = LaoPattern::Neighbourhood26, out.count = 26;
    else if (text == "54") out.pattern = LaoPattern::Rubik54, out.count = 54;
    else {
        std::string digits;
        if (text.rfind("fibonacci:", 0) == 0) digits = text.substr(10);
        else if (text.rfind("fib", 0) == 0) digits = text.substr(3);
        else return false;
        if (digits.empty() || digits.size() > 5 || digits.find_first_not_of("0123456789") != std::string::npos) return false;
        int k = std::atoi(digits.c_str());
        if (k < 1 || k > 4096) return false;
        out.pattern = LaoPattern::Fibonacci;
        out.count = k;
        out.jitter = 0;
    }
    return true;
}

}  // namespace curette
