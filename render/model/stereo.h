#pragma once
// Stereo pairs (docs/subsystems.md, "Stereo"). GL-free: the rig and the composition of two eye images;
// render/stereo_render.h renders them.
//
// The rig is off-axis: the eyes sit eyeSeparationMm apart on the camera's right axis, their view axes parallel
// to the camera's, each with an asymmetric frustum so that both image planes coincide. Parallax is then purely
// horizontal (a toed-in rig, each eye turned towards the target, adds vertical parallax that grows towards
// the image corners and bends the plane of zero parallax), zero at the convergence distance (the orbit
// target's: the volume straddles the screen), and both eyes share one camera frame: camera-space lights
// light both eyes from the same world direction, and the view-aligned slices of dos are the same planes.
//
// The renderer draws symmetric frusta only, so an eye's asymmetric frustum is taken as the columns of a wider
// symmetric one rendered from the eye: k more columns on each side (same fovy, same pixel pitch), the left eye
// keeping columns [2k, 2k + W), the right eye [0, W). Those columns are exactly the off-axis eye's rays when k
// is a whole number of pixels, so k is rounded and the convergence distance moves by that rounding
// (convergenceMm says where it is).
//
// Eye separation: 65 mm by default, the adult mean interpupillary distance, which is the orthostereo value: the
// scene is in real millimetres, and the default 30 degree fovy is what a monitor at arm's length subtends
// (a 27-inch 16:9 panel, 34 cm high, seen from 0.63 m), so the volume looks its real size and depth. The
// shipped head scenes put the head ~0.7 m away and ~0.17 m deep either side of the target: vergence from
// 1/0.52 to 1/0.86 dioptres around the screen's 1/0.69, a vergence-accommodation conflict of up to ~0.5 D,
// the order of the zone of comfort Shibata et al. (J. Vision 2011) measured at desktop distances. Smaller
// screens shrink the disparities; a bigger screen, a closer view or a deeper volume wants less
// (--eye-separation).

#include "render/model/frame.h"
#include "render/model/image.h"

#include <glm/glm.hpp>

#include <optional>
#include <string_view>

namespace curette {

enum class StereoMode { Off, SideBySide, Anaglyph };
const char* stereoModeName(StereoMode mode);          // "off", "side-by-side", "anaglyph"
std::optional<StereoMode> parseStereoMode(std::string_view name);
// The next mode in the viewer's cycle: off -> side-by-side -> anaglyph -> off.
StereoMode nextStereoMode(StereoMode mode);

enum class Eye { Left, Right };

constexpr double kDefaultEyeSeparationMm = 65.0;

struct StereoRig {
    FrameDescription centre;         // the mono frame the pair replaces
    double eyeSeparationMm = 0.0;
    int marginColumns = 0;           // k: columns an eye renders beyond the W it keeps, on each side
    double convergenceMm = 0.0;      // distance of zero parallax from the eyes' baseline (infinite when k = 0)

    // The frame an eye renders: the camera moved -+ eyeSeparationMm / 2 along its right axis, (W + 2k) x H.
    FrameDescription eyeFrame(Eye eye) const;
    // The first column of eyeFrame(eye)'s image the eye keeps (W columns from there): left 2k, right 0.
    int firstColumn(Eye eye) const;
};

StereoRig stereoRig(const FrameDescription& centre, double eyeSeparationMm);

// Columns [first, first + width) of `image`.
Image cropColumns(const Image& image, int first, int width);
// The rectangle of `size` pixels at `origin` (from the top left) of `image`.
Image cropImage(const Image& image, glm::ivec2 origin, glm::ivec2 size);
// Left eye on the left, right on the right: 2W x H (parallel free viewing, 3D displays' full side-by-side).
Image sideBySide(const Image& left, const Image& right);
// Red-cyan colour anaglyph: each eye composited over `background`, red from the left eye, green and blue from
// the right (red filter over the left eye). Opaque.
Image anaglyph(const Image& left, const Image& right, glm::vec4 background);
// The picture of `mode` (not Off) from two eye images.
Image composeStereo(StereoMode mode, const Image& left, const Image& right, glm::vec4 background);

}  // namespace curette
