#pragma once
// Renders stereo pairs (render/model/stereo.h): both eyes of the off-axis rig through one renderer, each cropped to
// its asymmetric frustum. The viewer's picture (StereoView) also lives here, on a texture for the Presenter.

#include "gl/objects.h"
#include "render/model/image.h"
#include "render/renderer.h"
#include "render/model/stereo.h"
#include "render/model/tracked_view.h"

#include <optional>

namespace curette {

struct StereoPair {
    StereoRig rig;
    Image left, right;   // each centre.size, premultiplied, as Renderer::readImage gives them
};

// Renders the left eye, then the right, and crops them (the renderer shows the right eye's frame afterwards).
StereoPair renderStereoPair(Renderer& renderer, const FrameDescription& centre, double eyeSeparationMm);

// One eye of a head-mounted display (render/model/tracked_view.h): its symmetric frame rendered, its pixels
// kept (eye.size, premultiplied). `view --xr` submits this image, `render --xr-views` composes it.
Image renderTrackedEye(Renderer& renderer, const TrackedEye& eye);

// The viewer's stereo picture of a window-sized frame: side-by-side gives each eye half the width (its own
// aspect, not squeezed: parallel free viewing), anaglyph the whole window. Renders only when the picture would
// differ from the one it holds.
class StereoView {
public:
    // Returns whether it rendered (false: the texture already holds this picture).
    bool update(Renderer& renderer, const FrameDescription& window, StereoMode mode, double eyeSeparationMm, glm::vec4 background);
    GLuint texture() const { return texture_.name(); }
    const Image& image() const { return image_; }

private:
    gl::Texture texture_;
    glm::ivec2 textureSize_{0};
    Image image_;
    std::optional<FrameDescription> window_;
    StereoMode mode_ = StereoMode::Off;
    double eyeSeparationMm_ = 0.0;
    glm::vec4 background_{0.0f};
    FrameDescription lastRightEye_;
};

}  // namespace curette
