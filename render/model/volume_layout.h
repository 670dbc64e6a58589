#pragma once
// How a volume-sized 3-D texture stores the scan's voxels. A volume whose every axis fits the GPU's
// GL_MAX_3D_TEXTURE_SIZE is stored as it is. One axis longer than the limit (the fold axis) is cut into P pieces
// of `stride` voxels plus one of overlap (a voxel on a cut is stored at the end of one piece and the start of
// the next), so trilinear filtering anywhere between two voxel centres reads one piece only; the pieces lie side
// by side along another axis (the across axis), one texel of zeros between them, in one texture of each kind.
// Every texture of the volume's size (V, V_o, V_m, V_PAO, V_AO, labels, drilled fraction) follows this layout;
// shaders/volume_layout.glsl maps voxels and texture coordinates with the uniforms it derives from it. Bricks
// keep the unfolded lattice. GL-free.

#include <glm/glm.hpp>

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

namespace curette {

struct VolumeLayout {
    glm::ivec3 dims{1};       // the volume's voxels
    int foldAxis = 0;         // the axis cut into pieces (meaningful when folded())
    int acrossAxis = 1;       // the axis the pieces lie along, side by side
    int pieces = 1;
    int stride = 1;           // voxels from one piece's first to the next's; a piece holds stride + 1
    glm::ivec3 texels{1};     // the texture's size

    // The layout for a GPU whose 3-D textures hold at most `maxTextureSize` texels per axis: unfolded when the
    // volume fits, else the fold of the one axis that does not, along the shortest other axis it fits beside.
    // Throws InputError(source, "dim", ...) when no such fold fits (two axes over the limit, or no room across).
    static VolumeLayout unfolded(glm::ivec3 dims);
    static VolumeLayout forLimit(glm::ivec3 dims, int maxTextureSize, const std::string& source);

    bool folded() const { return pieces > 1; }
    bool operator==(const VolumeLayout&) const = default;
    int pieceLength() const { return stride + 1; }
    int acrossPitch() const { return dims[acrossAxis] + 1; }   // texels from one piece's start to the next's, across
    // The piece that holds voxel index i of the fold axis as its own (the overlap voxel belongs to the later piece).
    int pieceOf(int i) const { return folded() ? std::min(i / stride, pieces - 1) : 0; }
    // Voxel v's texel in piece p (p must hold it).
    glm::ivec3 texelIn(glm::ivec3 v, int p) const;
    glm::ivec3 texel(glm::ivec3 v) const { return texelIn(v, pieceOf(v[foldAxis])); }
    // Whether voxel v is stored twice (the first voxel of every piece but the first), and its other texel.
    bool hasTwin(glm::ivec3 v) const;
    glm::ivec3 twinTexel(glm::ivec3 v) const { return texelIn(v, pieceOf(v[foldAxis]) - 1); }
    // Pieces p's voxels along the fold axis: [first, last].
    int pieceFirst(int p) const { return p * stride; }
    int pieceLast(int p) const { return std::min(p * stride + stride, dims[foldAxis] - 1); }

    std::size_t voxelCount() const { return std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z); }
    std::size_t texelCount() const { return std::size_t(texels.x) * std::size_t(texels.y) * std::size_t(texels.z); }
    // "unfolded" or e.g. "z folded into 2 pieces of 1051 along y: 512 x 1025 x 1051 texels (1.0005 texels a voxel)".
    std::string describe() const;

    // The texels of a volume given as voxels (x fastest), `fill` where no voxel is stored; and back.
    template <typename T>
    std::vector<T> fold(const std::vector<T>& voxels, T fill = T{}) const;
    template <typename T>
    std::vector<T> unfold(const std::vector<T>& texels) const;
};

template <typename T>
std::vector<T> VolumeLayout::fold(const std::vector<T>& voxels, T fill) const {
    if (!folded()) return voxels;
    std::vector<T> out(texelCount(), fill);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                glm::ivec3 v(x, y, z);
                const T& value = voxels[(std::size_t(z) * std::size_t(dims.y) + std::size_t(y)) * std::size_t(dims.x) + std::size_t(x)];
                auto put = [&](glm::ivec3 t) {
                    out[(std::size_t(t.z) * std::size_t(texels.y) + std::size_t(t.y)) * std::size_t(texels.x) + std::size_t(t.x)] = value;
                };
                put(texel(v));
                if (hasTwin(v)) put(twinTexel(v));
            }
    return out;
}

template <typename T>
std::vector<T> VolumeLayout::unfold(const std::vector<T>& stored) const {
    if (!folded()) return stored;
    std::vector<T> out(voxelCount());
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                glm::ivec3 t = texel(glm::ivec3(x, y, z));
                out[(std::size_t(z) * std::size_t(dims.y) + std::size_t(y)) * std::size_t(dims.x) + std::size_t(x)] =
                    stored[(std::size_t(t.z) * std::size_t(texels.y) + std::size_t(t.y)) * std::size_t(texels.x) + std::size_t(t.x)];
            }
    return out;
}

}  // namespace curette
