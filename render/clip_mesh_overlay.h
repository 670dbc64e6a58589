#pragma once
// The clip meshes themselves drawn over the rendered image: the planner sees the tools that carve (the
// resection sphere, the corridor), each in its own colour as a translucent fill with a crisp outline (its
// silhouette and creases), the held mesh in a highlight colour and more opaque (render/model/clip_mesh_display.h).
//
// Presentation, not a pass: it is outside the frame plan (render/model/frame_plan.h), declares no resource and
// never writes the renderer's images, so the exact frame stays what `curette render` gives, bit for bit
// (docs/architecture.md, "Preview and exact frames"). It draws either into the window after Presenter::present,
// or over a copy of an image it reads back (`render --show-meshes`).
//
// Each mesh is the vertex buffer step II draws (ClipMeshSet::vertexBuffer), placed by its RigidPose::matrix()
// and seen through the frame's OrbitCamera::viewProjection, the matrix the ray caster's pixel rays invert, so
// a mesh's outline lies where the image's clipping starts. Depth: the ray-cast image has none, so the meshes are
// drawn over the volume whatever lies in front of them; among themselves they are depth-tested, and a pixel
// shows the nearest mesh surface only (two passes: that surface's fill, normal and mesh into a buffer of the
// target's size, then the fill or the outline over the target).

#include "gl/objects.h"
#include "gl/program.h"
#include "render/model/clip_mesh_display.h"
#include "render/model/frame.h"
#include "render/model/image.h"

#include <glm/glm.hpp>

namespace curette {

namespace clip {
class ClipMeshSet;
}

class ClipMeshOverlay {
public:
    ClipMeshOverlay();
    ~ClipMeshOverlay();

    // Over the window's default framebuffer, into the rectangle at `origin` (top left, pixels) of `size` in a
    // framebuffer of `framebufferSize`: the rectangle Presenter::present drew `frame`'s image into. `heldMesh`:
    // the index of the held mesh in `meshes` (-1: none). Pixels outside the meshes keep their colour bit for bit.
    // `framebuffer` 0 is the window's; another framebuffer of that size stands for it (the tests).
    void draw(const clip::ClipMeshSet& meshes, const FrameDescription& frame, const ClipMeshDisplay& display, int heldMesh,
              glm::ivec2 origin, glm::ivec2 size, glm::ivec2 framebufferSize, GLuint framebuffer = 0);

    // A copy of `image` (RGBA32F, premultiplied, row 0 at the top, as Renderer::outputTexture) of `imageSize`
    // with the meshes drawn over it, read back. `image` itself is only read.
    Image drawOver(GLuint image, glm::ivec2 imageSize, const clip::ClipMeshSet& meshes, const FrameDescription& frame,
                   const ClipMeshDisplay& display, int heldMesh);

    // The crease angle of the outlines: a neighbouring pixel whose normal turns more is across an edge.
    static constexpr double creaseAngleDeg = 25.0;

private:
    // The meshes into the first pass's buffer of `size` (rows from the top when `rowsFromTop`), then the second
    // pass into the currently bound framebuffer's viewport at `viewportOrigin` (GL pixels, bottom left).
    void drawMeshes(const clip::ClipMeshSet& meshes, const FrameDescription& frame, const ClipMeshDisplay& display, int heldMesh,
                    glm::ivec2 size, bool rowsFromTop);
    void drawOutlines(GLuint targetFramebuffer, glm::ivec2 viewportOrigin, glm::ivec2 size);
    void ensureBuffer(glm::ivec2 size);

    gl::Program meshProgram_, outlineProgram_;
    gl::VertexArray meshVertexArray_, emptyVertexArray_;
    gl::Texture fill_, normalSlot_, outline_;
    gl::Renderbuffer depth_;
    gl::Framebuffer framebuffer_;
    glm::ivec2 bufferSize_{0};
};

}  // namespace curette
