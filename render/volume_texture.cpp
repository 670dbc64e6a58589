#include "render/volume_texture.h"

#include "base/error.h"

#include <algorithm>
#include <string>

namespace curette {

namespace {

// The part of a box of voxels [origin, origin + size) that piece p stores: its origin and size (size 0 along
// the fold axis when none).
struct PiecePart {
    glm::ivec3 origin, size;
};
PiecePart partInPiece(const VolumeLayout& layout, glm::ivec3 origin, glm::ivec3 size, int p, bool withOverlap) {
    const int a = layout.foldAxis;
    int first = layout.pieceFirst(p);
    int last = withOverlap || p == layout.pieces - 1 ? layout.pieceLast(p) : layout.pieceFirst(p + 1) - 1;
    int lo = std::max(origin[a], first), hi = std::min(origin[a] + size[a] - 1, last);
    PiecePart part{origin, size};
    part.origin[a] = lo;
    part.size[a] = std::max(0, hi - lo + 1);
    return part;
}

}  // namespace

gl::Texture createVolumeTexture(const VolumeLayout& layout, const VolumeTextureFormat& f, const char* label) {
    gl::Texture t = gl::createTexture(GL_TEXTURE_3D);
    glTextureStorage3D(t.name(), 1, f.internal, layout.texels.x, layout.texels.y, layout.texels.z);
    GLint filter = f.linear ? GL_LINEAR : GL_NEAREST;
    glTextureParameteri(t.name(), GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(t.name(), GL_TEXTURE_MAG_FILTER, filter);
    GLenum wrap = f.zeroBorder ? GL_CLAMP_TO_BORDER : GL_CLAMP_TO_EDGE;
    for (GLenum axis : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) glTextureParameteri(t.name(), axis, wrap);
    const float border[4] = {0, 0, 0, 0};
    glTextureParameterfv(t.name(), GL_TEXTURE_BORDER_COLOR, border);
    glObjectLabel(GL_TEXTURE, t.name(), -1, label);
    if (layout.folded()) glClearTexImage(t.name(), 0, f.format, f.type, nullptr);   // nullptr: zero
    if (glGetError() == GL_OUT_OF_MEMORY) throw SystemError(std::string("not enough GPU memory for ") + label);
    return t;
}

void uploadVolumeBox(GLuint texture, const VolumeLayout& layout, const VolumeTextureFormat& f, glm::ivec3 origin, glm::ivec3 size,
                     const void* data, glm::ivec2 dataExtent) {
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, dataExtent.x > 0 ? dataExtent.x : size.x);
    glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, dataExtent.y > 0 ? dataExtent.y : size.y);
    for (int p = 0; p < layout.pieces; ++p) {
        PiecePart part = partInPiece(layout, origin, size, p, true);
        if (part.size[layout.foldAxis] == 0) continue;
        glm::ivec3 skip = part.origin - origin;
        glPixelStorei(GL_UNPACK_SKIP_PIXELS, skip.x);
        glPixelStorei(GL_UNPACK_SKIP_ROWS, skip.y);
        glPixelStorei(GL_UNPACK_SKIP_IMAGES, skip.z);
        glm::ivec3 at = layout.texelIn(part.origin, p);
        glTextureSubImage3D(texture, 0, at.x, at.y, at.z, part.size.x, part.size.y, part.size.z, f.format, f.type, data);
    }
    for (GLenum p : {GL_UNPACK_ROW_LENGTH, GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SKIP_PIXELS, GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_IMAGES})
        glPixelStorei(p, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
}

void readVolume(GLuint texture, const VolumeLayout& layout, const VolumeTextureFormat& f, void* out) {
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);   // written by image stores: make them visible to the read-back
    const glm::ivec3 d = layout.dims;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_PACK_ROW_LENGTH, d.x);
    glPixelStorei(GL_PACK_IMAGE_HEIGHT, d.y);
    for (int p = 0; p < layout.pieces; ++p) {
        PiecePart part = partInPiece(layout, glm::ivec3(0), d, p, false);
        if (part.size[layout.foldAxis] == 0) continue;
        glPixelStorei(GL_PACK_SKIP_PIXELS, part.origin.x);
        glPixelStorei(GL_PACK_SKIP_ROWS, part.origin.y);
        glPixelStorei(GL_PACK_SKIP_IMAGES, part.origin.z);
        glm::ivec3 at = layout.texelIn(part.origin, p);
        // The buffer size the GL checks against: the whole volume (the skips address within it).
        glGetTextureSubImage(texture, 0, at.x, at.y, at.z, part.size.x, part.size.y, part.size.z, f.format, f.type,
                             static_cast<GLsizei>(layout.voxelCount() * std::size_t(f.bytesPerVoxel)), out);
    }
    for (GLenum p : {GL_PACK_ROW_LENGTH, GL_PACK_IMAGE_HEIGHT, GL_PACK_SKIP_PIXELS, GL_PACK_SKIP_ROWS, GL_PACK_SKIP_IMAGES})
        glPixelStorei(p, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
}

}  // namespace curette
