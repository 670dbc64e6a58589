#pragma once
// Volume-sized 3-D textures in a VolumeLayout (render/model/volume_layout.h): allocation at the layout's texel
// size, and uploads and read-backs of boxes of voxels, split into the pieces that store them (a voxel on a
// cut goes to both). The one place a volume texture's texels are addressed from the CPU.

#include "gl/objects.h"
#include "render/model/volume_layout.h"

#include <cstddef>
#include <vector>

namespace curette {

struct VolumeTextureFormat {
    GLenum internal;        // e.g. GL_R16
    GLenum format, type;    // the client data's, e.g. GL_RED, GL_UNSIGNED_SHORT
    int bytesPerVoxel;
    bool linear = true;     // GL_LINEAR (else GL_NEAREST, integer formats)
    bool zeroBorder = false;   // GL_CLAMP_TO_BORDER with border 0 (else GL_CLAMP_TO_EDGE)
};

// Storage for the layout's texels, every texel zero (the folded layout's gaps and the last piece's tail hold no
// voxel; a zero-border texture reads them as its border). Throws SystemError when the GPU is out of memory.
gl::Texture createVolumeTexture(const VolumeLayout& layout, const VolumeTextureFormat& f, const char* label);
// Uploads a box of voxels at voxel `origin` (`data`: x fastest, rows of `dataExtent.x` values and planes of
// `dataExtent.y` rows; 0: the box's own).
void uploadVolumeBox(GLuint texture, const VolumeLayout& layout, const VolumeTextureFormat& f, glm::ivec3 origin, glm::ivec3 size,
                     const void* data, glm::ivec2 dataExtent = glm::ivec2(0));
// Every voxel, x fastest (a voxel on a cut read from the piece that owns it).
void readVolume(GLuint texture, const VolumeLayout& layout, const VolumeTextureFormat& f, void* out);

template <typename T>
std::vector<T> readVolume(GLuint texture, const VolumeLayout& layout, const VolumeTextureFormat& f) {
    std::vector<T> values(layout.voxelCount());
    readVolume(texture, layout, f, values.data());
    return values;
}

}  // namespace curette
