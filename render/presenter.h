#pragma once
// The viewer's last step: the rendered image (premultiplied RGBA, row 0 at the top) drawn over the
// background into the window's default framebuffer (shaders/present.vert, present.frag). It sets all the
// GL state it needs, so viewer/ and tools/ issue no GL call of their own.

#include "gl/objects.h"
#include "gl/program.h"

#include <glm/glm.hpp>

namespace curette {

class Presenter {
public:
    Presenter();
    // `image` into the rectangle at `origin` (top left, pixels) of `size` in a framebuffer of `framebufferSize`,
    // the rest of the framebuffer cleared to the background (the side bar's panels are drawn over it).
    void present(GLuint image, glm::ivec2 origin, glm::ivec2 size, glm::ivec2 framebufferSize, glm::vec4 background);
    // The whole framebuffer in the background colour (the window before its first image: the side bar says what
    // is being prepared).
    void clear(glm::ivec2 framebufferSize, glm::vec4 background);

private:
    gl::Program program_;
    gl::VertexArray emptyVertexArray_;
};

}  // namespace curette
