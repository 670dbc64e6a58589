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
    void present(GLuint image, glm::ivec2 framebufferSize, glm::vec4 background);

private:
    gl::Program program_;
    gl::VertexArray emptyVertexArray_;
};

}  // namespace curette
