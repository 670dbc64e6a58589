#include "render/model/stereo.h"

#include "base/error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace curette {

namespace {

struct StereoModeName {
    StereoMode mode;
    const char* name;
};
constexpr StereoModeName kStereoModes[] = {
    {StereoMode::Off, "off"}, {StereoMode::SideBySide, "side-by-side"}, {StereoMode::Anaglyph, "anaglyph"}};

}  // namespace

const char* stereoModeName(StereoMode mode) {
    for (const StereoModeName& m : kStereoModes)
        if (m.mode == mode) return m.name;
    return "?";
}

std::optional<StereoMode> parseStereoMode(std::string_view name) {
    for (const StereoModeName& m : kStereoModes)
        if (name == m.name) return m.mode;
    return std::nullopt;
}

StereoMode nextStereoMode(StereoMode mode) {
    for (std::size_t i = 0; i < std::size(kStereoModes); ++i)
        if (kStereoModes[i].mode == mode) return kStereoModes[(i + 1) % std::size(kStereoModes)].mode;
    return StereoMode::Off;
}

StereoRig stereoRig(const FrameDescription& centre, double eyeSeparationMm) {
    StereoRig rig;
    rig.centre = centre;
    rig.eyeSeparationMm = eyeSeparationMm;
    // A point on the camera axis at the target's distance D lies s = separation / 2 beside each eye's axis:
    // s / (2 D tan(fovy / 2)) of the image height, i.e. delta pixels from the eye image's centre column.
    const double tanHalfY = std::tan(glm::radians(centre.camera.fovYDeg) / 2.0);
    const double halfSeparation = eyeSeparationMm / 2.0;
    const double delta = halfSeparation * centre.size.y / (2.0 * centre.camera.distanceMm * tanHalfY);
    rig.marginColumns = static_cast<int>(std::lround(delta));
    rig.convergenceMm = rig.marginColumns > 0 ? halfSeparation * centre.size.y / (2.0 * rig.marginColumns * tanHalfY)
                                              : std::numeric_limits<double>::infinity();
    return rig;
}

FrameDescription StereoRig::eyeFrame(Eye eye) const {
    FrameDescription f = centre;
    f.camera = centre.camera.movedRight((eye == Eye::Left ? -0.5 : 0.5) * eyeSeparationMm);
    f.size.x = centre.size.x + 2 * marginColumns;
    return f;
}

int StereoRig::firstColumn(Eye eye) const { return eye == Eye::Left ? 2 * marginColumns : 0; }

Image cropColumns(const Image& image, int first, int width) {
    if (first < 0 || width < 0 || first + width > image.width)
        throw std::logic_error("cropColumns: columns outside the image");
    Image out;
    out.width = width;
    out.height = image.height;
    out.pixels.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(image.height));
    for (int y = 0; y < image.height; ++y)
        std::copy_n(&image.at(first, y), width, &out.at(0, y));
    return out;
}

Image cropImage(const Image& image, glm::ivec2 origin, glm::ivec2 size) {
    if (origin.x < 0 || origin.y < 0 || size.x < 0 || size.y < 0 || origin.x + size.x > image.width || origin.y + size.y > image.height)
        throw std::logic_error("cropImage: rectangle outside the image");
    Image out;
    out.width = size.x;
    out.height = size.y;
    out.pixels.resize(static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y));
    for (int y = 0; y < size.y; ++y)
        std::copy_n(&image.at(origin.x, origin.y + y), size.x, &out.at(0, y));
    return out;
}

Image sideBySide(const Image& left, const Image& right) {
    if (left.height != right.height) throw std::logic_error("sideBySide: eye images of different heights");
    Image out;
    out.width = left.width + right.width;
    out.height = left.height;
    out.pixels.resize(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height));
    for (int y = 0; y < out.height; ++y) {
        std::copy_n(&left.at(0, y), left.width, &out.at(0, y));
        std::copy_n(&right.at(0, y), right.width, &out.at(left.width, y));
    }
    return out;
}

Image anaglyph(const Image& left, const Image& right, glm::vec4 background) {
    if (left.width != right.width || left.height != right.height) throw std::logic_error("anaglyph: eye images of different sizes");
    // Each eye over the straight background, as toRgba8 composites, as straight colour (the anaglyph is opaque).
    auto over = [&](glm::vec4 c) {
        float a = c.a + (1.0f - c.a) * background.a;
        glm::vec3 premultiplied = glm::vec3(c) + (1.0f - c.a) * background.a * glm::vec3(background);
        return a > 0.0f ? premultiplied / a : glm::vec3(0.0f);
    };
    Image out;
    out.width = left.width;
    out.height = left.height;
    out.pixels.resize(left.pixels.size());
    for (std::size_t i = 0; i < out.pixels.size(); ++i) {
        glm::vec3 l = over(left.pixels[i]), r = over(right.pixels[i]);
        out.pixels[i] = glm::vec4(l.r, r.g, r.b, 1.0f);
    }
    return out;
}

Image composeStereo(StereoMode mode, const Image& left, const Image& right, glm::vec4 background) {
    switch (mode) {
        case StereoMode::SideBySide: return sideBySide(left, right);
        case StereoMode::Anaglyph: return anaglyph(left, right, background);
        case StereoMode::Off: break;
    }
    throw std::logic_error("composeStereo: no stereo mode");
}

}  // namespace curette
