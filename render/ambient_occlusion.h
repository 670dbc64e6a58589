#pragma once
// Contextual Ambient Occlusion (seed 002): steps I, IV and V of DESIGN.md's CAO table.
//   I   precompute(): LAO of every voxel without clipping -> V_PAO
//   IV  update():     anti-aliased voxel clipping -> V_o (clipped opacity) and V_m (categories a/b/c)
//   V   update():     V_AO: category c copies V_PAO, b (and a voxels next to a visible one) recompute LAO
// A CAO update visits only the voxels whose category can differ from c now or could at the previous update
// (the bounding box of both frames' mesh regions); everywhere else V_o, V_AO are what a whole-grid pass would
// write again. V_m outside that box may still say b from an earlier `lao` update: only step V reads it, and
// only inside the box.
// Shading `lao` is the baseline CAO is measured against: the same passes without the dilation test, so every
// visible voxel recomputes. Both produce bit-identical V_AO (the exactness contract, tested).
//
// Stored (only for lao/cao shading): V_o R16 (opacity per TF unit length), V_m R8UI, V_PAO R16, V_AO R16,
// and in the compacted variant a recompute list of 4 bytes per voxel.

#include "clip/clip_mesh_set.h"
#include "render/gl/program.h"
#include "render/gl/timer.h"
#include "render/gpu_volume.h"
#include "render/lao_directions.h"
#include "render/shading_mode.h"
#include "render/transfer_function_texture.h"

#include <optional>
#include <vector>

namespace curette {

struct GpuAllocation;

struct LaoSettings {
    LaoDirectionSet directions;
    int samples = 20;                // M, samples per ray (eq. 2); the paper's Engine scene uses 20
    double stepMm = 1.0;             // distance between LAO samples (the paper: 1 mm)
    int antiAliasingSamples = 32;    // N of Algorithm 2 (the paper: 32)
    // Shading: colour = TF colour * ambientScale * A. With 2 an open flat surface (A = 0.5) shows its TF
    // colour (the reference implementation also doubles LAO). Not part of V_AO, so not of the contract.
    double ambientScale = 2.0;
    // Step V: a full-grid dispatch that decides per voxel (early exit), or a compacted list of the voxels to
    // recompute (atomic append + indirect dispatch). `curette bench cao` measures both (its "Step V dispatch"
    // table): on the head at K = 26 the compacted list took 710 ms against 982 ms for the grid (both over the
    // CAO dispatch region), 803 against 1645 ms when both still visited the whole volume.
    enum class Dispatch { Compacted, FullGrid } dispatch = Dispatch::Compacted;

    bool operator==(const LaoSettings& o) const {
        return directions.pattern == o.directions.pattern && directions.count == o.directions.count &&
               directions.jitter == o.directions.jitter && directions.seed == o.directions.seed &&
               directions.skyWeighting == o.directions.skyWeighting && samples == o.samples && stepMm == o.stepMm &&
               antiAliasingSamples == o.antiAliasingSamples && dispatch == o.dispatch && ambientScale == o.ambientScale;
    }
};

// The N extra anti-aliasing offsets of step IV (Algorithm 2, line 9) in voxel index units: Halton points
// (bases 2, 3, 5) in [-1, 1]^3, fixed so every run classifies the same. One definition for the GPU buffer and
// the CPU twin.
std::vector<glm::dvec3> antiAliasingOffsets(int count);

struct AmbientOcclusionStats {
    std::uint64_t voxels = 0;
    std::uint64_t dispatched = 0;      // voxels steps IV and V visited (the dispatch region, below)
    std::uint64_t recomputed = 0;      // voxels whose LAO ray ran in step V
    double recomputedFraction() const { return voxels ? double(recomputed) / double(voxels) : 0.0; }
};

class AmbientOcclusion {
public:
    AmbientOcclusion(const GpuVolume& volume, const LaoSettings& settings);
    ~AmbientOcclusion();

    const LaoSettings& settings() const { return settings_; }
    // The farthest LAO sample from its voxel: (M - 1) * step (lao_ray.glsl).
    double reachMm() const { return reachMm(settings_); }
    static double reachMm(const LaoSettings& settings);
    // The radius around the clip meshes within which a voxel's AO can change (derivation in the .cpp).
    double dilationRadiusMm() const { return dilationRadiusMm(settings_, volume_.geometry()); }
    static double dilationRadiusMm(const LaoSettings& settings, const VolumeGeometry& geometry);

    // Step I for the volume under `tf`. Call again when the TF or the settings change.
    void precompute(const TransferFunctionTexture& tf, gl::TimerSet* timers = nullptr);
    // Steps IV and V under the meshes' current poses. mode: Cao (masked) or Lao (every visible voxel).
    void update(const TransferFunctionTexture& tf, const clip::ClipMeshSet& clip, ShadingMode mode,
                gl::TimerSet* timers = nullptr);

    GLuint ambientTexture() const { return ambient_.name(); }
    const AmbientOcclusionStats& lastStats() const { return stats_; }
    std::vector<GpuAllocation> allocations() const;

    // Read-backs for tests and `replay --check` (x fastest).
    std::vector<std::uint16_t> readAmbient() const;
    std::vector<std::uint16_t> readPrecomputed() const;
    std::vector<std::uint16_t> readOpacity() const;
    std::vector<std::uint8_t> readMask() const;

private:
    // A box of voxels [origin, origin + size) that steps IV and V visit.
    struct VoxelRegion {
        glm::ivec3 origin{0}, size{0};
        bool empty() const { return size.x <= 0 || size.y <= 0 || size.z <= 0; }
        std::uint64_t voxels() const { return empty() ? 0 : std::uint64_t(size.x) * std::uint64_t(size.y) * std::uint64_t(size.z); }
    };
    VoxelRegion wholeVolume() const { return {glm::ivec3(0), volume_.geometry().dims}; }
    // The voxels whose category can be a or b under the meshes' current poses (their map boxes, padded).
    VoxelRegion meshRegion(const clip::ClipMeshSet& clip) const;
    void runVoxelClipping(const TransferFunctionTexture& tf, const clip::ClipMeshSet* clip, bool testDilation,
                          const VoxelRegion& region);
    void runLao(GLuint target, bool compacted, float opacityExponent, const VoxelRegion& region);
    void setLaoUniforms(gl::Program& program, float opacityExponent);

    const GpuVolume& volume_;
    LaoSettings settings_;
    gl::Texture opacity_, mask_, precomputed_, ambient_;
    gl::Buffer directions_, antiAliasing_, list_, dispatch_;
    gl::ComputeVariants clipPrograms_{"voxel_clip.comp"};
    gl::Program laoProgram_, compactProgram_;
    AmbientOcclusionStats stats_;
    bool precomputed_valid_ = false;
    // Outside this region (of the last update) V_o holds the unclipped opacity and V_AO equals V_PAO, so the
    // next CAO update only visits it and its own mesh region. Unset after step I (V_AO not yet written).
    std::optional<VoxelRegion> lastMeshRegion_;
};

}  // namespace curette
