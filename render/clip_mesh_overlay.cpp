#include "render/clip_mesh_overlay.h"

#include "base/error.h"
#include "render/passes/clip_mesh_set.h"

#include <cmath>
#include <cstddef>

namespace curette {

ClipMeshOverlay::ClipMeshOverlay()
    : meshProgram_(gl::Program::graphics("clip_mesh_overlay.vert", "clip_mesh_overlay.frag")),
      outlineProgram_(gl::Program::graphics("present.vert", "clip_mesh_outline.frag")),
      meshVertexArray_(gl::createVertexArray()),
      emptyVertexArray_(gl::createVertexArray()) {
    using Corner = clip::ClipMeshSet::CornerVertex;
    for (GLuint attribute : {0u, 1u}) {
        glEnableVertexArrayAttrib(meshVertexArray_.name(), attribute);
        glVertexArrayAttribFormat(meshVertexArray_.name(), attribute, 3, GL_FLOAT, GL_FALSE,
                                  attribute == 0 ? offsetof(Corner, position) : offsetof(Corner, normal));
        glVertexArrayAttribBinding(meshVertexArray_.name(), attribute, 0);
    }
    outlineProgram_.set("creaseCosine", static_cast<float>(std::cos(creaseAngleDeg * 3.14159265358979323846 / 180.0)));
}

ClipMeshOverlay::~ClipMeshOverlay() = default;

void ClipMeshOverlay::ensureBuffer(glm::ivec2 size) {
    if (size == bufferSize_ && framebuffer_) return;
    auto makeTexture = [&](GLenum format, const char* label) { return gl::createPixelBuffer2D(format, size.x, size.y, label); };
    fill_ = makeTexture(GL_RGBA16F, "clip-mesh overlay fill");
    normalSlot_ = makeTexture(GL_RGBA16F, "clip-mesh overlay normal and mesh");
    outline_ = makeTexture(GL_RGBA8, "clip-mesh overlay outline colour");
    depth_ = gl::createRenderbuffer();
    glNamedRenderbufferStorage(depth_.name(), GL_DEPTH_COMPONENT32F, size.x, size.y);
    framebuffer_ = gl::createFramebuffer();
    glNamedFramebufferTexture(framebuffer_.name(), GL_COLOR_ATTACHMENT0, fill_.name(), 0);
    glNamedFramebufferTexture(framebuffer_.name(), GL_COLOR_ATTACHMENT1, normalSlot_.name(), 0);
    glNamedFramebufferTexture(framebuffer_.name(), GL_COLOR_ATTACHMENT2, outline_.name(), 0);
    const GLenum drawBuffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glNamedFramebufferDrawBuffers(framebuffer_.name(), 3, drawBuffers);
    glNamedFramebufferRenderbuffer(framebuffer_.name(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_.name());
    if (glCheckNamedFramebufferStatus(framebuffer_.name(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw SystemError("clip-mesh overlay framebuffer is incomplete");
    bufferSize_ = size;
}

void ClipMeshOverlay::drawMeshes(const clip::ClipMeshSet& meshes, const FrameDescription& frame, const ClipMeshDisplay& display,
                                 int heldMesh, glm::ivec2 size, bool rowsFromTop) {
    ensureBuffer(size);
    const float zero[4] = {0, 0, 0, 0}, farDepth = 1.0f;
    for (GLint i = 0; i < 3; ++i) glClearNamedFramebufferfv(framebuffer_.name(), GL_COLOR, i, zero);
    glClearNamedFramebufferfv(framebuffer_.name(), GL_DEPTH, 0, &farDepth);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.name());
    glViewport(0, 0, size.x, size.y);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);   // open meshes and the inside of a mesh the camera is in show too
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    meshProgram_.set("viewProjection", glm::mat4(frame.camera.viewProjection(frame.size)));
    meshProgram_.set("eyeWorld", glm::vec3(frame.camera.position()));
    meshProgram_.set("flipY", rowsFromTop ? -1.0f : 1.0f);
    meshProgram_.use();
    glBindVertexArray(meshVertexArray_.name());
    for (int i = 0; i < meshes.count(); ++i) {
        bool held = i == heldMesh;
        meshProgram_.set("localToWorld", glm::mat4(meshes.pose(i).matrix()));
        meshProgram_.set("meshColor", held ? kHeldClipMeshColor : clipMeshColor(i));
        meshProgram_.set("fillOpacity", static_cast<float>(held ? heldFillOpacity(display) : display.fillOpacity));
        meshProgram_.set("outlineOpacity", static_cast<float>(held ? heldOutlineOpacity(display) : display.outlineOpacity));
        meshProgram_.set("meshSlot", static_cast<float>(i + 1));
        glVertexArrayVertexBuffer(meshVertexArray_.name(), 0, meshes.vertexBuffer(i), 0, sizeof(clip::ClipMeshSet::CornerVertex));
        glDrawArrays(GL_TRIANGLES, 0, meshes.vertexCount(i));
    }
    glDisable(GL_DEPTH_TEST);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
}

void ClipMeshOverlay::drawOutlines(GLuint targetFramebuffer, glm::ivec2 viewportOrigin, glm::ivec2 size) {
    glBindFramebuffer(GL_FRAMEBUFFER, targetFramebuffer);
    glViewport(viewportOrigin.x, viewportOrigin.y, size.x, size.y);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_SCISSOR_TEST);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);   // premultiplied "over"
    glBindTextureUnit(0, fill_.name());
    glBindTextureUnit(1, normalSlot_.name());
    glBindTextureUnit(2, outline_.name());
    outlineProgram_.set("viewportOrigin", viewportOrigin);
    outlineProgram_.use();
    glBindVertexArray(emptyVertexArray_.name());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
}

void ClipMeshOverlay::draw(const clip::ClipMeshSet& meshes, const FrameDescription& frame, const ClipMeshDisplay& display, int heldMesh,
                           glm::ivec2 origin, glm::ivec2 size, glm::ivec2 framebufferSize, GLuint framebuffer) {
    if (meshes.count() == 0 || size.x <= 0 || size.y <= 0) return;
    drawMeshes(meshes, frame, display, heldMesh, size, false);
    drawOutlines(framebuffer, glm::ivec2(origin.x, framebufferSize.y - origin.y - size.y), size);   // GL's origin is bottom left
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

Image ClipMeshOverlay::drawOver(GLuint image, glm::ivec2 imageSize, const clip::ClipMeshSet& meshes, const FrameDescription& frame,
                                const ClipMeshDisplay& display, int heldMesh) {
    gl::Texture copy = gl::createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(copy.name(), 1, GL_RGBA32F, imageSize.x, imageSize.y);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);   // the image is written by image stores
    glCopyImageSubData(image, GL_TEXTURE_2D, 0, 0, 0, 0, copy.name(), GL_TEXTURE_2D, 0, 0, 0, 0, imageSize.x, imageSize.y, 1);
    if (meshes.count() > 0) {
        gl::Framebuffer target = gl::createFramebuffer();
        glNamedFramebufferTexture(target.name(), GL_COLOR_ATTACHMENT0, copy.name(), 0);
        if (glCheckNamedFramebufferStatus(target.name(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw SystemError("clip-mesh overlay image framebuffer is incomplete");
        // Texture row 0 is the picture's top, so the meshes are drawn with rows from the top too.
        drawMeshes(meshes, frame, display, heldMesh, imageSize, true);
        drawOutlines(target.name(), glm::ivec2(0), imageSize);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    Image out;
    out.width = imageSize.x;
    out.height = imageSize.y;
    out.pixels.resize(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height));
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    glGetTextureImage(copy.name(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(out.pixels.size() * sizeof(glm::vec4)), out.pixels.data());
    return out;
}

}  // namespace curette
