#pragma once
// A frame as a plan of passes (the Filament frame-graph model; docs/architecture.md "The frame and its plan"). One
// table declares every pass: its name (the one the timings, the benches, the viewer overlay and
// `curette render --plan` print), the paper step it implements, and the resources it reads and writes. One
// function, planFrame, turns the shading mode, what the scene has, and what is already up to date into the
// ordered list of passes the renderer runs. Passes whose outputs are current are left out, so a still scene
// costs step VI alone.

#include "render/model/gpu_resources.h"
#include "render/model/shading_mode.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace curette {

enum class Pass {
    ClipMaps,        // CAO steps II-III
    LaoPrecompute,   // step I
    VoxelClipping,   // step IV
    LaoRecompute,    // step V
    TubeGBuffer,     // seed 000 section 3.1.1
    RayCast,         // step VI
    SlabPass,        // seed 001 Algorithms 1, 3; seed 000 Algorithms 2-4
    Composite,       // seed 000 Algorithms 5, 6
    IsmosRayCast,    // seed 003 pass 1: ray casting with depth layers and the transmittance fit
    IsmosOcclusion,  // seed 003 pass 2: image-space occlusion, sections 3.3-3.7
    GradientVolume,  // phong's central differences per voxel, once per volume (render/gradient_volume.h)
    Count
};

struct PassInfo {
    Pass id;
    const char* name;
    const char* implements;
    std::vector<Resource> reads, writes;   // every resource the pass may touch; planFrame keeps those in use
    bool ambientOcclusion;                 // counted as the frame's AO time
    const char* activity;                  // what it computes, in a planner's words (the viewer's progress bar)
};

const PassInfo& passInfo(Pass pass);
std::span<const PassInfo> allPasses();

// What is already up to date, in one place (the renderer keeps it; planFrame reads it). Each derived
// product records the versions of the inputs it was computed from; a product is current when they match.
struct InputVersions {
    std::uint64_t volume = 1, transferFunction = 1, laoSettings = 1;
    std::uint64_t clipMeshes = 1;   // clip::ClipMeshSet::version(): poses, scales, meshes added or removed
    std::uint64_t removal = 0;      // plan::RemovalVolume::version() of the drilled removal: an input of V_o and V_AO, not V_PAO
    bool operator==(const InputVersions&) const = default;
};

// `now` is always the renderer's current versions; Freshness keeps only what each product was computed from.
class Freshness {
public:
    // V_PAO: volume, TF and LAO settings.
    bool precomputedCurrent(const InputVersions& now) const;
    // Whether two sets of versions give the same V_PAO (volume, TF, LAO settings: the clip meshes do not count).
    static bool samePrecomputeInputs(const InputVersions& a, const InputVersions& b);
    // V_AO (and V_o, V_m): V_PAO's inputs, the clip meshes and the mode (cao and lao write the same V_AO but
    // visit different voxels, so a mode change reruns IV and V).
    bool ambientCurrent(const InputVersions& now, ShadingMode mode) const;
    void markPrecomputed(const InputVersions& now) { precomputed_ = now, ambient_.reset(); }
    void markAmbient(const InputVersions& now, ShadingMode mode) { ambient_ = now, ambientMode_ = mode; }
    void forgetAmbientOcclusion() { precomputed_.reset(), ambient_.reset(); }

private:
    std::optional<InputVersions> precomputed_, ambient_;
    ShadingMode ambientMode_ = ShadingMode::Solid;
};

// What the scene has this frame, and what of it is current.
struct PlanInputs {
    ShadingMode shading = ShadingMode::Phong;
    int clipMeshes = 0;
    bool clipMapsCurrent = true;   // every mesh's maps (and the dilated ones if the mode needs them) drawn
    bool labels = false;           // the scene has a label volume
    bool drilled = false;          // ... and a drilled removal (plan/removal_volume.h)
    bool tubes = false;            // the scene has tubes ...
    bool tubesInView = false;      // ... and they may cover a pixel of this frame
    bool precomputedCurrent = false;
    bool ambientCurrent = false;
    bool ismosExact = false;       // ismos: exact layer opacities (the layer backs) ...
    bool ismosFit = false;         // ... or the transmittance fit
    bool gradientVolume = false;   // phong reads its gradients from the gradient volume (an 8-bit scan) ...
    bool gradientVolumeCurrent = false;   // ... which is built
};

struct PlannedPass {
    Pass pass;
    std::vector<Resource> reads, writes;   // the declared ones this frame uses
};

struct FramePlan {
    std::vector<PlannedPass> passes;
    bool runs(Pass pass) const;
    // Whether `pass` runs and reads `resource` this frame (its declared read, kept when the frame has it).
    bool reads(Pass pass, Resource resource) const;
    // One line a pass: "name  (implements)  reads -> writes".
    std::string describe() const;
};

FramePlan planFrame(const PlanInputs& inputs);

// Time per pass of the frames since the last collection (ms); names come from the pass table.
struct FrameTimings {
    struct Entry {
        Pass pass;
        double ms;
    };
    std::vector<Entry> passes;
    double ms(Pass pass) const;
    double ambientOcclusionMs() const;   // the passes the table marks as AO (steps I, IV, V)
    double totalMs() const;
};

}  // namespace curette
