#pragma once
// The slab pass: view-aligned slices marched front to back, one compute dispatch per slice, carrying an
// eye buffer and a ping-pong occlusion buffer (Directional Occlusion Shading, seed 001; with tubes, the
// combined occlusion of seed 000). Used for `dos` shading and, once tubes are in a scene, for every mode.

#include "render/passes/clip_mesh_set.h"
#include "render/model/frame.h"
#include "gl/program.h"
#include "render/gpu_volume.h"
#include "render/shader_pieces.h"
#include "render/model/slice_lattice.h"
#include "render/transfer_function_texture.h"
#include "render/passes/tube_set.h"

#include <algorithm>
#include <cstdint>

namespace curette {

// What one run of the slab pass reads and where it writes.
struct SlabInputs {
    const FrameDescription& frame;        // camera, size, shading, lights, frame.dos
    const GpuVolume& volume;
    const TransferFunctionTexture& tf;
    const clip::ClipMeshSet& clip;
    SampleShadingPiece shading;           // the mode's colour; V_AO and its scale in lao/cao
    GLuint eyeBuffer = 0;                 // RGBA32F, frame.size: the image
    GBuffer* tubes = nullptr;             // a filled G-buffer: tubes take part, the partial occlusion is written
    double geometryOpacity = 0.0;         // what a tube crossing absorbs in the occlusion buffer (seed 000 Algorithm 3)
    double tubeThicknessMm = 1.0;         // the depth it absorbs that over (dos_slice.comp)
};

// Where a run of the slab pass in slices is. Its unit is a band of rows of one view-aligned slice: a slice reads
// the last one's occlusion around each pixel, so slices run in order, but its pixels are independent, so a
// slice may be dispatched in bands (one slice at full size can take longer than a frame on llvmpipe). The run
// writes the pass's buffers, so another run begun meanwhile (a preview's) makes it stale: advance() refuses
// it, and the caller begins again (Renderer: a preview restarts the exact frame).
struct SlabRun {
    long first = 0, last = -1;             // the slices k in [first, last], k * distanceMm deep along the view
    double distanceMm = 0;
    int bandsPerSlice = 1, rowsPerBand = 0;
    long next = 0;                         // the next unit: slice first + next / bandsPerSlice, band next % bandsPerSlice
    int current = 0;                       // occlusion_[current] holds what the slices done let through
    std::uint64_t generation = 0;          // the begin() it belongs to
    long slices() const { return std::max(0L, last - first + 1); }
    long units() const { return slices() * bandsPerSlice; }
    long left() const { return std::max(0L, units() - next); }
    bool done() const { return next >= units(); }
};

class SlabPass {
public:
    static constexpr long maxSlices = kMaxSlabSlices;
    // A slice is dispatched in bands of this many rows of work groups (fewer when the image has fewer): a run
    // of an image `height` rows high has bandsPerSlice(height) units a slice.
    static constexpr int kGroupRowsPerBand = 12;
    static int bandsPerSlice(int height);

    // The whole pass: begin() and every slice.
    void run(const SlabInputs& in);
    // The pass in slices, bit for bit the whole one: begin() clears the eye buffer and the occlusion (and the tubes'
    // partial occlusion) and returns the run; advance() dispatches its next `count` units (bands of a slice; at
    // most those left), each exactly as run() does, from inputs equal to begin()'s. Every call sets the program and its bindings
    // afresh, so whatever ran between two calls (another pass, the window's own drawing) changes nothing.
    SlabRun begin(const SlabInputs& in);
    void advance(const SlabInputs& in, SlabRun& run, long count);

    double resolveSliceDistanceMm(const DosSettings& settings, const GpuVolume& volume) const;
    int slicesLastFrame() const { return slices_; }
    // The occlusion buffer after the last slice (tests: all channels must stay in [0, 1]).
    std::vector<glm::vec2> readOcclusion() const;
    // Tests only: false stores the occlusion buffer without the final clamp to [0, 1] (a separate program
    // variant; the default one is untouched), so readOcclusion() shows what the update computed.
    void setClampOcclusion(bool clamp) { clampOcclusion_ = clamp; }
    std::size_t gpuBytes() const;

private:
    // `frameDefines`: the clip meshes', cut faces', lights' and volume layout's (ClipMeshSet::addDefines,
    // SampleShadingPiece::addCutFaceDefines, addLightingDefines, NoDataPiece, VolumeLayoutPiece).
    gl::Program& program(ShadingMode mode, bool tubes, const TransferFunctionTexture& tf, gl::Defines frameDefines);
    void ensureBuffers(glm::ivec2 size);
    // The program of `in` with every uniform and binding the slices share.
    gl::Program& prepare(const SlabInputs& in, double sliceDistanceMm);

    gl::ComputeVariants programs_{"dos_slice.comp"};
    gl::Texture occlusion_[2];
    glm::ivec2 size_{0};
    int slices_ = 0;
    int last_ = 0;
    std::uint64_t generation_ = 0;
    bool clampOcclusion_ = true;
};

}  // namespace curette
