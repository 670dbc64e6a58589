#pragma once
// A CPU image (render/model/image.h) as a GL texture for the viewer's panels (the slice views: an
// ImGui::Image of name()), RGBA8 composited over black. Storage is made again only when the size changes.

#include "gl/objects.h"
#include "render/model/image.h"

#include <glm/glm.hpp>

namespace curette {

class ImageTexture {
public:
    // Uploads `image` (premultiplied RGBA, row 0 at the top: texture row 0 is the image's top row, so ImGui
    // draws it upright with the default uv (0,0)-(1,1)). Pixels are shown magnified without blur (nearest).
    void update(const Image& image);
    GLuint name() const { return texture_.name(); }
    glm::ivec2 size() const { return size_; }

private:
    gl::Texture texture_;
    glm::ivec2 size_{0};
};

}  // namespace curette
