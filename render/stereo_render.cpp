#include "render/stereo_render.h"

#include <algorithm>

namespace curette {

StereoPair renderStereoPair(Renderer& renderer, const FrameDescription& centre, double eyeSeparationMm) {
    StereoPair pair;
    pair.rig = stereoRig(centre, eyeSeparationMm);
    for (Eye eye : {Eye::Left, Eye::Right}) {
        renderer.render(pair.rig.eyeFrame(eye));
        (eye == Eye::Left ? pair.left : pair.right) = cropColumns(renderer.readImage(), pair.rig.firstColumn(eye), centre.size.x);
    }
    return pair;
}

Image renderTrackedEye(Renderer& renderer, const TrackedEye& eye) {
    renderer.render(eye.frame);
    return cropImage(renderer.readImage(), eye.cropOrigin, eye.size);
}

bool StereoView::update(Renderer& renderer, const FrameDescription& window, StereoMode mode, double eyeSeparationMm, glm::vec4 background) {
    FrameDescription centre = window;
    if (mode == StereoMode::SideBySide) centre.size.x = std::max(1, window.size.x / 2);
    // Current when nothing changed since the right eye (rendered last) was drawn.
    if (window_ && *window_ == window && mode_ == mode && eyeSeparationMm_ == eyeSeparationMm && background_ == background &&
        renderer.showing(lastRightEye_))
        return false;
    StereoPair pair = renderStereoPair(renderer, centre, eyeSeparationMm);
    image_ = composeStereo(mode, pair.left, pair.right, background);
    lastRightEye_ = pair.rig.eyeFrame(Eye::Right);
    window_ = window;
    mode_ = mode;
    eyeSeparationMm_ = eyeSeparationMm;
    background_ = background;
    glm::ivec2 size(image_.width, image_.height);
    if (!texture_ || size != textureSize_) {
        texture_ = gl::createTexture(GL_TEXTURE_2D);
        glTextureStorage2D(texture_.name(), 1, GL_RGBA32F, size.x, size.y);
        glTextureParameteri(texture_.name(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(texture_.name(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glObjectLabel(GL_TEXTURE, texture_.name(), -1, "stereo picture");
        textureSize_ = size;
    }
    glTextureSubImage2D(texture_.name(), 0, 0, 0, size.x, size.y, GL_RGBA, GL_FLOAT, image_.pixels.data());
    return true;
}

}  // namespace curette
