#pragma once
// The valid values of the settings both a scene file and code can set: one table, read by the scene reader
// (scene/scene_keys.cpp) and by the passes that check what code hands them (render/passes/ambient_occlusion.cpp,
// slab_pass.cpp), so a value one accepts the other cannot refuse.

#include <string>

namespace curette {

struct IntLimit {
    int min, max;
    bool contains(int v) const { return v >= min && v <= max; }
    std::string expected() const;   // "an integer in [1, 16]"
};

struct NumberLimit {
    double min, max;
    bool maxOpen = false;   // max itself is outside
    bool contains(double v) const { return v >= min && (maxOpen ? v < max : v <= max); }
    std::string expected() const;   // "a number in [0, 90)"
};

// Throws InputError(source, key, limit.expected(), value) when `value` is outside `limit`.
void requireWithin(const IntLimit& limit, int value, const std::string& source, const std::string& key);
void requireWithin(const NumberLimit& limit, double value, const std::string& source, const std::string& key);

namespace limits {
// "ambient_occlusion" (LaoSettings).
inline constexpr IntLimit laoSamples{1, 1024};
inline constexpr NumberLimit laoStepMm{1e-3, 100};
inline constexpr IntLimit laoAntiAliasingSamples{0, 256};
// "dos" (DosSettings). The cone's base radius is d tan(theta) (DOS eq. 11-12): theta stays below 90 degrees.
inline constexpr NumberLimit dosConeAngleDeg{0, 90, true};
inline constexpr IntLimit dosGrid{1, 16};
inline constexpr NumberLimit dosSliceDistanceMm{0, 100};
inline constexpr NumberLimit dosAmbient{0, 100};
}  // namespace limits

}  // namespace curette
