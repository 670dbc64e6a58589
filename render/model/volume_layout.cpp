#include "render/model/volume_layout.h"

#include "base/error.h"

#include <algorithm>
#include <cstdio>

namespace curette {

VolumeLayout VolumeLayout::unfolded(glm::ivec3 dims) {
    VolumeLayout l;
    l.dims = l.texels = dims;
    l.stride = dims[l.foldAxis];
    return l;
}

VolumeLayout VolumeLayout::forLimit(glm::ivec3 dims, int maxTextureSize, const std::string& source) {
    VolumeLayout l = unfolded(dims);
    const std::string limit = "GL_MAX_3D_TEXTURE_SIZE " + std::to_string(maxTextureSize);
    int over = -1;
    for (int axis = 0; axis < 3; ++axis) {
        if (dims[axis] < 1)
            throw InputError(source, "dim[" + std::to_string(axis + 1) + "]", "at least 1 voxel", std::to_string(dims[axis]));
        if (dims[axis] <= maxTextureSize) continue;
        if (over >= 0)
            throw InputError(source, "dim", "at most one axis longer than " + limit + " (it is folded into pieces)",
                             std::to_string(dims.x) + " x " + std::to_string(dims.y) + " x " + std::to_string(dims.z));
        over = axis;
    }
    if (over < 0) return l;
    // Fewest pieces whose length (stride + 1 overlap voxel) fits; the last piece is shorter, never empty.
    const int n = dims[over];
    l.foldAxis = over;
    l.pieces = (n + maxTextureSize - 2) / (maxTextureSize - 1);
    l.stride = (n + l.pieces - 1) / l.pieces;
    // Across the shortest other axis: P pieces and P - 1 zero texels between them.
    int a = (over + 1) % 3, b = (over + 2) % 3;
    l.acrossAxis = dims[a] <= dims[b] ? a : b;
    long long across = static_cast<long long>(l.pieces) * (dims[l.acrossAxis] + 1) - 1;
    if (maxTextureSize < 2 || (l.pieces - 1) * l.stride >= n || across > maxTextureSize)
        throw InputError(source, "dim[" + std::to_string(over + 1) + "]",
                         "a length that folds into pieces of at most " + limit + " beside each other",
                         std::to_string(dims.x) + " x " + std::to_string(dims.y) + " x " + std::to_string(dims.z));
    l.texels[l.foldAxis] = l.pieceLength();
    l.texels[l.acrossAxis] = static_cast<int>(across);
    return l;
}

glm::ivec3 VolumeLayout::texelIn(glm::ivec3 v, int p) const {
    if (!folded()) return v;
    v[foldAxis] -= p * stride;
    v[acrossAxis] += p * acrossPitch();
    return v;
}

bool VolumeLayout::hasTwin(glm::ivec3 v) const {
    int i = v[foldAxis];
    return folded() && i > 0 && i % stride == 0 && i / stride < pieces;
}

std::string VolumeLayout::describe() const {
    auto size = [](glm::ivec3 d) { return std::to_string(d.x) + " x " + std::to_string(d.y) + " x " + std::to_string(d.z); };
    if (!folded()) return "one 3D texture of " + size(texels) + " texels";
    const char* axes = "xyz";
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.4f", double(texelCount()) / double(voxelCount()));
    return std::string(1, axes[foldAxis]) + " folded into " + std::to_string(pieces) + " pieces of " + std::to_string(pieceLength()) +
           " voxels side by side along " + axes[acrossAxis] + ": one 3D texture of " + size(texels) + " texels (" + ratio +
           " texels a voxel)";
}

}  // namespace curette
