#pragma once
// One frame's run through its plan (docs/architecture.md, "The frame plan"): the context every pass runs from,
// the progress of a run that goes in slices, the one rule that sizes slices, and the stamp that says what an
// image shows. The renderer has one executor (Renderer::execute) for exact frames, previews and exact frames in
// slices; they differ only in the run they hand it.

#include "gl/objects.h"
#include "render/model/frame.h"
#include "render/model/frame_plan.h"
#include "render/pass_bindings.h"
#include "render/passes/slab_pass.h"
#include "render/recast_region.h"
#include "render/shader_pieces.h"

#include <cstdint>
#include <optional>

namespace curette {

// What an image shows: the frame and the versions of the scene's inputs it was rendered from. Equal stamps
// mean equal images, so the viewer keeps no dirty flags of its own.
struct ImageStamp {
    FrameDescription frame;
    InputVersions versions;
    std::uint64_t appearance = 0;   // inputs of the image no AO product depends on (tubes, the ambient scale)
    bool operator==(const ImageStamp&) const = default;
};

// Where a preview's ambient factor comes from (lao/cao frames; other modes preview as they render).
enum class PreviewAmbient {
    None,          // V_PAO is not there yet (step I in progress): the frame is shaded phong instead
    Precomputed,   // V_PAO, the unclipped LAO (no exact frame since step I)
    LastExact,     // V_AO of the last exact frame (its poses, not this frame's, near the cut)
};

// The size of the next slice of a pass that runs in slices (step I's bricks, step IV's work units, step V's list
// groups, the ray cast's bands): the measured rate times the budget left, within [1, left]; `probe` units
// before any rate is known; `fixed` > 0 sets the size (tests). The slab pass's slices are its view-aligned
// slices (one dispatch each).
//  - Rate::Last: the last slice's rate, and at most twice the last slice: its units may have been cheap (air at
//    the top of the image, voxels far from the cut), so a wrong rate overruns the budget little.
//  - Rate::Slowest: the slowest rate since restart(). Step I: bricks no visible sample reads cost a fraction
//    of the others (LaoSettings::onlyWhereSeen), so a rate measured in the air around a head would size the
//    first slice in tissue many times over the budget.
class SliceSizer {
public:
    enum class Rate { Last, Slowest };
    explicit SliceSizer(Rate rule) : rule_(rule) {}
    std::uint32_t next(double budgetMs, std::uint32_t left, std::uint32_t probe, std::uint32_t fixed);
    // A slice of `units` took `ms` of wall time (GPU waited for); slices under half a millisecond are not timed.
    void measured(std::uint32_t units, double ms);
    void restart() { unitsPerMs_ = 0, last_ = 0; }
    // A new run of the same work: the rate carries over, the last slice's size does not (a frame's first slice
    // is not capped by the tail of the one before).
    void newRun() { last_ = 0; }

private:
    Rate rule_;
    double unitsPerMs_ = 0;
    std::uint32_t last_ = 0;
};

// The pixels an exact frame's ray cast covers (render/recast_region.h) and their tiles, made at its first cast.
struct RecastTiles {
    PixelRegion region;
    std::optional<TileSpans> spans;
    gl::Buffer spanBuffer;
};

// What a pass runs from: nothing of it is modal renderer state, so a preview and an exact frame differ here only.
struct PassContext {
    const FrameDescription& frame;       // the frame the image passes shade (a preview during step I: as phong)
    const FrameDescription& mapsFrame;   // the frame the clip maps are drawn for (its own mode's maps)
    const FramePlan& plan;               // the plan the pass belongs to
    GLuint image;                        // the image the image passes write
    GLuint ambient;                      // what lao/cao shade with: V_AO, or a preview's V_PAO (0: none yet)
    RecastTiles* recast;                 // the exact ray cast's pixels (null: every pixel)
};

// A frame's run through its plan, whole (render, renderPreview) or in slices (advanceExact).
struct FrameRun {
    FrameDescription frame;      // the frame asked for
    FrameDescription shaded;     // ... as its image passes shade it
    FramePlan plan{};
    bool exact = true;           // an exact frame (the exact image), or a preview (the preview image)
    PreviewAmbient ambient = PreviewAmbient::None;   // a preview's ambient source
    ImageStamp stamp;            // the scene as the run began or its last slice ended ...
    std::uint64_t previews = 0;  // ... and the previews drawn by then (a preview overwrites the G-buffer and layers)
    std::size_t next = 0;        // the pass of plan.passes under way
    bool imageBegun = false;     // its first image pass ran (the last exact image is gone)
    // The sliced passes' progress.
    bool stepIVBegun = false, stepVBegun = false, stepVDone = false;
    InputVersions ambientVersions{};   // what step IV clipped: V_AO's freshness once step V is done
    std::uint32_t stepIVUnits = 0, stepVGroups = 0;
    int parts = -1, partsDone = 0;   // the ray cast's parts of bands (TileOrderPiece; -1: not begun)
    std::int64_t tubeUnitsDone = -1;  // the tube G-buffer's units drawn (-1: not cleared yet)
    int compositeRowsDone = 0;        // the composite's rows
    std::optional<SlabRun> slab{};   // the slab pass's (none: not begun)
    std::optional<RecastTiles> recast{};
    std::vector<BoundResources> bound{};   // per pass run, what its programs bound (Renderer::setAuditBindings)
};

}  // namespace curette
