#pragma once
// A clip mesh's depth intervals (clip_test.glsl: front < z < back at the pixel holding a point), summarised over
// square blocks of pixels so a region of many pixels is asked in a few lookups: per interval and per level k,
// the largest front and the smallest back over each aligned block of 2^k x 2^k pixels. Conservative: a query
// reads the blocks covering its pixels (and some around them), so "holds" is never said where one pixel does
// not. Step IV uses it to find the bricks whose every clip sample lies inside a mesh (render/mesh_voxel_box.h).
// GL-free: built from the maps read back once per map render.

#include <glm/glm.hpp>

#include <vector>

namespace curette {

class DepthIntervalPyramid {
public:
    DepthIntervalPyramid() = default;
    // `fronts[j]`, `backs[j]`: interval j's front and back over resolution^2 pixels (x fastest), empty pixels
    // +inf and -inf.
    DepthIntervalPyramid(int resolution, const std::vector<std::vector<float>>& fronts, const std::vector<std::vector<float>>& backs);

    int resolution() const { return resolution_; }
    // Whether one interval holds every depth of [zLo, zHi] at every pixel of the rectangle [lo, hi] (inclusive,
    // within the map): front < zLo and zHi < back throughout.
    bool intervalHolds(glm::ivec2 lo, glm::ivec2 hi, double zLo, double zHi) const;

private:
    struct Level {
        int side = 0;
        std::vector<float> maxFront, minBack;
    };
    int resolution_ = 0;
    std::vector<std::vector<Level>> intervals_;   // [interval][level]
};

}  // namespace curette
