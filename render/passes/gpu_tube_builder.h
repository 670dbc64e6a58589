#pragma once
// Tubes expanded from their swept rings on the GPU (issue 12): the CPU sweeps each streamline once
// (sweepTubeRings: cleaning, smoothing, rotation-minimising frames, colours; render/model/tube_geometry.h) and
// uploads 64 bytes per ring; shaders/tube_build.comp writes the `sides` vertices of every ring, the quads
// between rings and the caps into the vertex and index streams a TubeSet draws, in expandTubeRings' layout
// (the CPU expansion is its oracle: same indices and colours, positions and normals within float rounding).
// The uploaded rings are freed when the build returns; only the vertex streams stay.
//
// Shader-storage blocks are limited in size (GL_MAX_SHADER_STORAGE_BLOCK_SIZE: 128 MiB on llvmpipe), so the
// streamlines are expanded in batches whose every bound range fits, each range bound at an offset aligned to
// GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT (the shader is told how far into the range its first element is).

#include "render/model/tube_geometry.h"
#include "render/passes/tube_set.h"

namespace curette {

struct GpuTubeBuildStats {
    std::size_t batches = 0;
    std::size_t ringBytes = 0;   // uploaded ring and streamline records (the largest batch's rings alive at once)
};

// `batchBytes` caps every bound range of a batch (below the GL limit; tests make it small to force many
// batches at unaligned offsets). Throws SystemError when one streamline alone needs more than that.
inline constexpr std::size_t defaultTubeBatchBytes = std::size_t(64) << 20;
TubeBuffers buildTubeBuffersOnGpu(const TubeRings& rings, GpuTubeBuildStats* stats = nullptr, std::size_t batchBytes = defaultTubeBatchBytes);

}  // namespace curette
