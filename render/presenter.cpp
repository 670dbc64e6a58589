#include "render/presenter.h"

namespace curette {

Presenter::Presenter()
    : program_(gl::Program::graphics("present.vert", "present.frag")), emptyVertexArray_(gl::createVertexArray()) {}

void Presenter::clear(glm::ivec2 framebufferSize, glm::vec4 background) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, framebufferSize.x, framebufferSize.y);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(background.r * background.a, background.g * background.a, background.b * background.a, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
}

void Presenter::present(GLuint image, glm::ivec2 origin, glm::ivec2 size, glm::ivec2 framebufferSize, glm::vec4 background) {
    clear(framebufferSize, background);
    glViewport(origin.x, framebufferSize.y - origin.y - size.y, size.x, size.y);   // GL's origin is bottom left
    glDisable(GL_DEPTH_TEST);
    glBindTextureUnit(0, image);
    program_.set("background", background);
    program_.use();
    glBindVertexArray(emptyVertexArray_.name());
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace curette
