#pragma once
// Contextual Ambient Occlusion (seed 002): steps I, IV and V (docs/architecture.md, "The frame and its plan").
//   I   precompute(): LAO of every voxel without clipping -> V_PAO
//   IV  update():     anti-aliased voxel clipping -> V_o (clipped opacity) and V_m (categories a/b/c)
//   V   update():     V_AO: category c copies V_PAO, b (and a voxels next to a visible one) recompute LAO,
//                     in CAO only in bricks within LAO reach of a V_o step IV changed (render/model/lao_reach.h);
//                     elsewhere the rays read only step I's V_o, so they copy V_PAO
// A CAO update visits only the voxels whose V_o or V_AO the meshes can change now or could at the previous
// update: the bricks (render/mesh_voxel_box.h, 4^3 voxels) where a mesh's oriented dilated box and its reach ball
// meet, in either frame; everywhere else V_o, V_AO are what a whole-grid pass would write again. V_m outside
// those bricks may be stale (b from an earlier `lao` update, or c where a dilated shape reaches past its ball):
// only step V reads it, at visited voxels and at the 26 neighbours of visited clipped ones, which lie within a
// cell diagonal of the mesh, inside its box and ball, and so are visited too.
// Shading `lao` is the baseline CAO is measured against: the same passes without the dilation test, so every
// visible voxel recomputes. Both produce bit-identical V_AO (the exactness contract, tested).
//
// Stored (only for lao/cao shading): V_o R16 (opacity per TF unit length), V_m R8UI, V_PAO R16, V_AO R16,
// and in the compacted variant a recompute list of 4 bytes per voxel; the visited-brick list, 4 bytes per brick.

#include "render/passes/clip_mesh_set.h"
#include "mesh/coverage.h"
#include "gl/program.h"
#include "render/model/gpu_resources.h"
#include "render/gpu_volume.h"
#include "render/model/lao_directions.h"
#include "render/model/lao_reach.h"
#include "render/model/lao_settings.h"
#include "render/mesh_voxel_box.h"
#include "render/model/shading_mode.h"
#include "render/removal_texture.h"
#include "render/transfer_function_texture.h"
#include "plan/removal_volume.h"

#include <optional>
#include <vector>

namespace curette {

// The N extra anti-aliasing offsets of step IV (Algorithm 2, line 9), defined in mesh/coverage.h.
using clip::antiAliasingOffsets;

struct AmbientOcclusionStats {
    std::uint64_t voxels = 0;
    std::uint64_t dispatched = 0;      // voxels steps IV and V visited (the visited bricks, below)
    std::uint64_t bricks = 0;          // bricks steps IV and V visited
    std::uint64_t laoBricks = 0;       // of those, bricks where LAO can change (render/model/lao_reach.h)
    std::uint64_t sampledBricks = 0;   // of those, bricks where step IV tests clip samples (within a mesh's reach)
    std::uint64_t deepBricks = 0;      // and bricks deep inside a mesh, every sample inside without a test
    std::uint64_t recomputed = 0;      // voxels whose LAO ray ran in step V
    double recomputedFraction() const { return voxels ? double(recomputed) / double(voxels) : 0.0; }
};

// The share of step I's time the LAO phase takes (the rest is its voxel clipping), for its progress bar: on the
// carved head (K = 26, M = 20) phase 1 costs about 2 % of step I on llvmpipe.
inline constexpr double kLaoShareOfPrecompute = 0.98;

class AmbientOcclusion {
public:
    // `seenBricks`: per brick of GpuVolume::seenBrickSize voxels, 0 where a sample may have opacity
    // (Renderer::updateOccupancy); it must outlive this object. With settings.onlyWhereSeen, the voxels of the
    // other bricks, which no visible sample reads, get V_AO = 1 without a ray. Null: every voxel's LAO is computed.
    AmbientOcclusion(const GpuVolume& volume, const LaoSettings& settings, const gl::Texture* seenBricks = nullptr);
    ~AmbientOcclusion();

    const LaoSettings& settings() const { return settings_; }
    // The farthest LAO sample from its voxel: (M - 1) * step (lao_ray.glsl).
    double reachMm() const { return reachMm(settings_); }
    static double reachMm(const LaoSettings& settings);
    // The radius around the clip meshes within which a voxel's AO can change (derivation in the .cpp).
    double dilationRadiusMm() const { return dilationRadiusMm(settings_, volume_.geometry()); }
    static double dilationRadiusMm(const LaoSettings& settings, const VolumeGeometry& geometry);

    // The passes of the frame plan (render/model/frame_plan.h); the renderer decides when each runs (its Freshness
    // record says what V_PAO and V_AO were computed from).
    // Step I for the volume under `tf`. Run again when the TF or the settings change.
    void precompute(const TransferFunctionTexture& tf);
    // Step I in slices, so a viewer keeps presenting while it runs (docs/architecture.md, "Preview and exact
    // frames"): beginPrecompute() forgets V_PAO and starts over; each advancePrecompute(tf, bricks) runs the next
    // `bricks` bricks (4^3 voxels, in brick-number order: z-slabs) of phase 1 (step IV without meshes into V_o and
    // V_m, every brick) and then of phase 2 (the LAO of every voxel into V_PAO, which reads the V_o of every
    // brick within reach, so it starts only when phase 1 is complete), and returns the bricks it ran. Every voxel
    // is computed by the same invocation code as in one dispatch, so the result is the same bit for bit
    // (Precompute.SlicedEqualsOneDispatch). precompute() is begin + one slice of everything.
    void beginPrecompute();
    std::uint32_t advancePrecompute(const TransferFunctionTexture& tf, std::uint32_t bricks);
    bool precomputeStarted() const { return precomputeStarted_; }
    bool precomputeDone() const { return precomputeStarted_ && slicedBricks_ == 2 * totalBricks(); }
    // Work done of step I in [0, 1]; phase 2 (the rays) counts as `kLaoShareOfPrecompute` of it.
    double precomputeProgress() const;
    std::uint32_t totalBricks() const;
    // Which phase the next slice belongs to: 0 voxel clipping, 1 LAO, 2 done.
    int precomputePhase() const;
    GLuint precomputedTexture() const { return precomputed_.name(); }
    // Step IV under the meshes' current poses. mode: Cao (masked, over the visited bricks) or Lao (every
    // voxel). Must follow step I.
    void clipVoxels(const TransferFunctionTexture& tf, const clip::ClipMeshSet& clip, ShadingMode mode);
    // Step IV in slices (Renderer::advanceExact): beginClipVoxels decides and uploads the bricks to visit and
    // returns their work in units (a brick where clip samples are tested counts kTestedBrickCost, any other one);
    // each advanceClipVoxels(units) clips the voxels of the next `units` of it, the same share of each kind of
    // brick, so slices of equal units cost alike (the meshes must not change in between), and returns how many
    // it ran. Each voxel is clipped by the same invocation code as in one dispatch, so V_o and V_m come out the
    // same bit for bit. clipVoxels is begin and one slice of all.
    static constexpr std::uint32_t kTestedBrickCost = 5;   // about five bricks beyond reach on llvmpipe (docs/measurements.md)
    std::uint32_t beginClipVoxels(const clip::ClipMeshSet& clip, ShadingMode mode);
    std::uint32_t advanceClipVoxels(const TransferFunctionTexture& tf, const clip::ClipMeshSet& clip, std::uint32_t units);
    std::uint32_t clipUnitsLeft() const { return clipUnits_ - clipUnitsDone_; }
    // Step V over the bricks step IV just visited.
    void recomputeLao(const TransferFunctionTexture& tf);
    // Step V in slices (Renderer::advanceExact): beginRecompute(tf) decides every visited voxel (copies and
    // unreachable voxels are written at once), builds the recompute list and returns its LAO work in groups
    // of kLaoGroupSize entries; each advanceRecompute(groups) computes the next `groups` of them and returns
    // how many it ran. Each voxel's LAO is its own, so after the last slice V_AO is what recomputeLao() writes,
    // bit for bit (Cao.SlicedStepVEqualsOneDispatch). The full-grid dispatch (a baseline) is not sliced:
    // beginRecompute runs it whole and returns 0.
    static constexpr std::uint32_t kLaoGroupSize = 64;   // lao.comp's local size
    std::uint32_t beginRecompute(const TransferFunctionTexture& tf);
    std::uint32_t advanceRecompute(std::uint32_t groups);
    std::uint32_t recomputeGroupsLeft() const { return recomputeGroups_ - recomputeGroupsDone_; }
    // The drill's accumulated removal (plan/removal_volume.h), an input of V_o and V_AO but not of V_PAO (step I
    // leaves it out). A CAO update also visits the bricks within the dilation radius of every brick the removal
    // changed since the last update (their V_o and the LAO around them change), and counts the drilled bricks
    // it does not visit as changed V_o (markLaoBricks); step IV makes voxels near a drilled one category b.
    // Both must outlive this object; null: no drilling.
    void setRemoval(const plan::RemovalVolume* removal, const RemovalTexture* texture);

    // The update under way (step IV begun, in slices or whole, and step V not finished) will not be finished: the
    // viewer moved on during the exact frame in slices. The next update visits every brick this one visited as
    // well as its own meshes' bricks, so V_o, V_m and V_AO come out as if this update had finished
    // (ExactInSlices.MotionDuringTheExactFrameAbandonsItsStepV...). V_AO is not that of any one pose until then.
    void abandonUpdate();

    GLuint ambientTexture() const { return ambient_.name(); }
    const AmbientOcclusionStats& lastStats() const { return stats_; }
    std::vector<GpuAllocation> allocations() const;   // V_o, V_m, V_PAO, V_AO, recompute list, directions

    // Read-backs for tests and `replay --check` (x fastest).
    std::vector<std::uint16_t> readAmbient() const;
    std::vector<std::uint16_t> readPrecomputed() const;
    std::vector<std::uint16_t> readOpacity() const;
    std::vector<std::uint8_t> readMask() const;

private:
    // Uploads the visited bricks' list (shaders/visit_bricks.glsl) for the next passes, flagged "LAO can
    // change" everywhere or nowhere (then markLaoBricks sets it after step IV); returns their number. Step IV
    // knows the clip-sample count of two kinds of brick without a test (render/mesh_voxel_box.h): those deep inside
    // a mesh (`deep`) and those beyond every mesh's reach (outside `withinReach`). The list holds the others first,
    // then the deep ones, then those beyond, each part dealt to the worker threads on its own.
    std::uint32_t uploadVisit(const BrickSet& bricks, const BrickSet& withinReach, const BrickSet& deep, bool laoEverywhere);
    // Between steps IV and V of a CAO update: flags the visited bricks within LAO reach of a brick whose V_o
    // step IV changed (render/model/lao_reach.h).
    void markLaoBricks();
    void setVisitUniforms(gl::Program& program) const;
    void setDecisionUniforms(gl::Program& program) const;
    // Step IV from progress `from` to `to` (of clipUnits_): the same share of each part of the uploaded list
    // (uploadVisit), each by its program: the one that tests clip samples, or one compiled with the count known.
    enum class SampleCount { Tested, AllInside, NoneInside };
    void runVoxelClipping(const TransferFunctionTexture& tf, const clip::ClipMeshSet* clip, bool testDilation, bool applyDrill,
                          std::uint32_t from, std::uint32_t to);
    void dispatchVoxelClipping(const TransferFunctionTexture& tf, const clip::ClipMeshSet* clip, bool testDilation, bool applyDrill,
                               SampleCount count, std::uint32_t firstSlot, std::uint32_t slots);
    void runLao(GLuint target, bool compacted, float opacityExponent);
    // Binds lao.comp's resources and uniforms to the variant for `opacityExponent`, and returns it.
    gl::Program& bindLao(GLuint target, float opacityExponent);
    gl::Defines laoDefines(float opacityExponent) const;
    gl::Program& laoProgram(float opacityExponent);   // compiled when first needed
    // lao_compact.comp over the visited slots [firstSlot, firstSlot + bricks): appends their voxels to recompute to
    // the list, or with countChunks counts them per chunk of countChunks slots (into the list's entries).
    void buildRecomputeList(std::uint32_t firstSlot, std::uint32_t bricks, std::uint32_t countChunks = 0);
    void resetListLength();         // listCount = 0 before a chunk's list is appended
    void readRecomputeCounts();     // the list's length and the LAO rays run, into listCount_ and stats_
    void setLaoUniforms(gl::Program& program, float opacityExponent);

    const GpuVolume& volume_;
    LaoSettings settings_;
    const gl::Texture* seenBricks_;   // null, or when settings_.onlyWhereSeen is off: LAO everywhere
    gl::Texture opacity_, mask_, precomputed_, ambient_;
    gl::Buffer directions_, antiAliasing_, list_, dispatch_, visitBricks_;
    int directionCount_ = 0;   // K, the length of the uploaded direction list (LAO_DIRECTIONS)
    gl::ComputeVariants clipPrograms_{"voxel_clip.comp"};
    gl::ComputeVariants laoPrograms_{"lao.comp"};   // by laoDefines
    gl::Program compactProgram_;
    AmbientOcclusionStats stats_;
    std::uint32_t listCount_ = 0;            // the recompute list's length (read after it is built)
    // The recompute list holds the voxels of at most listChunkBricks_ visited bricks at a time, so it costs
    // 4 bytes a voxel of a chunk, not of the volume (a first exact frame visits every brick); step V runs chunk
    // after chunk. CURETTE_RECOMPUTE_LIST_BRICKS sets it (tests make small volumes take several chunks).
    static constexpr std::uint32_t kListChunkBricks = 16384;   // 1 Mi voxels, 4 MiB
    std::uint32_t listChunkBricks_ = kListChunkBricks;
    std::size_t listCapacity_ = 0;               // entries: a chunk's voxels, then one count per chunk
    std::size_t chunkCountsAt_ = 0;              // where the counts begin (beginRecompute's counting pass)
    std::vector<std::uint32_t> chunkEntries_;    // sliced step V: each chunk's list length
    std::uint32_t chunk_ = 0, chunkGroupsDone_ = 0;
    bool chunkBuilt_ = false;
    std::uint32_t recomputeGroups_ = 0, recomputeGroupsDone_ = 0;   // sliced step V
    float recomputeExponent_ = 1;
    std::uint32_t visitCount_ = 0;   // bricks in the uploaded list: what the last step IV visited, step V visits the same
    std::uint32_t clipUnits_ = 0, clipUnitsDone_ = 0;   // step IV's work over them and its progress (in slices)
    std::uint32_t testedSlots_ = 0;     // of them, the first, where step IV tests clip samples (uploadVisit)
    std::uint32_t deepSlotsEnd_ = 0;    // then up to here the bricks deep inside a mesh; the rest lie beyond reach
    bool clipDilation_ = false;         // step IV tests the dilated maps (cao)
    bool laoFlagsPending_ = false;   // a CAO list without its "LAO can change" flags yet: markLaoBricks before step V
    LaoReachBricks laoReach_;
    const plan::RemovalVolume* removal_ = nullptr;
    const RemovalTexture* removalTexture_ = nullptr;
    std::uint64_t removalApplied_ = 0;   // the removal's version the last update's V_o holds
    bool applyDrill_ = false;            // the voxel clipping under way scales V_o by the drilled removal
    // The last update's meshes and the bricks each reached (render/mesh_voxel_box.h). Outside the bricks of a mesh
    // V_o, V_m and V_AO hold what they would without it, and where it reached they hold what its state then
    // made them; so the next CAO update visits the bricks of the meshes that changed since (their old and new
    // ones) and leaves the others'. Unset after step I (V_AO not yet written).
    struct MeshBricks {
        clip::RigidPose pose;
        glm::dvec3 scale{1.0};
        const clip::TriangleMesh* geometry = nullptr;
        BrickSet bricks;
        bool sameMesh(const MeshBricks& o) const { return pose == o.pose && scale == o.scale && geometry == o.geometry; }
    };
    struct UpdateMeshes {
        std::uint64_t mapRenders = 0;   // the maps drawn again (resolution, dilation radius): every mesh changed
        std::vector<MeshBricks> meshes;
    };
    std::optional<UpdateMeshes> lastUpdate_;
    // The bricks of the meshes this update leaves, where it does not visit: their V_o may be clipped. Step V counts
    // those clipped when step IV last visited them as changed (markLaoBricks), or all of them while that is not
    // known for every brick (after step I, and after a full LAO update, until a CAO update has visited every brick).
    BrickSet stillBricks_;
    std::vector<std::uint8_t> clippedBricks_;   // per brick: step IV clipped a voxel with opacity when it last visited it
    bool clippedBricksKnown_ = false;
    // The bricks the last step IV visited: what an abandoned update leaves to the next one (carried_).
    std::optional<BrickSet> lastVisit_, carried_;
    // Sliced step I: bricks done over both phases (0 .. 2 * totalBricks()); the whole grid's brick numbers.
    bool precomputeStarted_ = false;
    std::uint32_t slicedBricks_ = 0;
    std::vector<std::uint32_t> allBricks_;
    void uploadVisitRange(std::uint32_t first, std::uint32_t count);
};

}  // namespace curette
