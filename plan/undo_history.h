#pragma once
// Undo and redo of drill strokes and setting edits, in one history, in the order they were made. A stroke
// (drill control pressed .. released, over any number of frames) is one step, stored as brick-sparse
// differences: the masks of the bricks it changed, before and after (plan/removal_volume.h). A setting edit
// is one step holding the edits that undo it and those that redo it, opaque here: JSON arrays of the session's
// edits (scene/setting_edit.h), which the session reads back and applies (session/drilling.h). Ctrl+Z undoes
// the last step of either kind; a new step drops the redo steps. The history is bounded by memory, not by a
// count: when the steps held exceed the budget the oldest are forgotten (the removal and settings are kept).

#include "plan/removal_volume.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <deque>
#include <optional>
#include <string>

namespace curette::plan {

inline constexpr std::size_t kDefaultUndoBudgetBytes = std::size_t(256) << 20;

// What an undo or redo did: nothing (no step), a stroke's masks restored into the removal, or an edit step
// whose edits (a JSON array) the caller applies.
struct UndoResult {
    bool done = false;
    nlohmann::json edits;   // null for a stroke
    explicit operator bool() const { return done; }
};

class UndoHistory {
public:
    explicit UndoHistory(std::size_t budgetBytes = kDefaultUndoBudgetBytes) : budget_(budgetBytes) {}

    // A stroke: begin, then each frame's RemovalVolume::apply with before() as its record, then end. end()
    // makes it one undo step (when it changed anything) and clears the redo steps.
    void beginStroke();
    bool strokeOpen() const { return open_.has_value(); }
    BrickMaskMap* before() { return open_ ? &*open_ : nullptr; }
    void endStroke(const RemovalVolume& removal);

    // A setting edit (one frame's panel edits): the edits that undo it, in the order to apply them, and those
    // that redo it (JSON arrays). Ends an open stroke first; clears the redo steps. One drag of a panel's
    // slider edits a setting every frame: an edit with a `mergeKey` (the setting and its target) made the frame
    // after the last step, an edit with the same key, joins it (keeps its undo, takes this redo), so the drag
    // is one step. Frames are counted by endFrame(); a frame without this edit (the release) ends the drag.
    void pushEdit(const RemovalVolume& removal, nlohmann::json undoEdits, nlohmann::json redoEdits, const std::string& mergeKey = {});
    void endFrame() { ++frame_; }

    // Undo / redo the last step. An open stroke is ended first.
    UndoResult undo(RemovalVolume& removal);
    UndoResult redo(RemovalVolume& removal);
    std::size_t undoSteps() const { return undo_.size(); }
    std::size_t redoSteps() const { return redo_.size(); }
    std::size_t bytes() const { return bytes_; }                 // held by every step
    std::size_t lastStrokeBytes() const { return lastStrokeBytes_; }
    std::size_t budgetBytes() const { return budget_; }

private:
    struct Step {
        BrickMaskMap before, after;                 // a stroke
        nlohmann::json undoEdits, redoEdits;        // an edit (arrays; null for a stroke)
        std::string mergeKey;                       // an edit's, when a next frame's may join it
        std::uint64_t frame = 0;                    // when it was made or last joined
        std::size_t bytes = 0;
    };
    void push(Step step);
    // Undo (from undo_ to redo_) or redo (the other way) of the last step: a stroke's masks set back, or its edits returned.
    UndoResult moveLast(RemovalVolume& removal, std::deque<Step>& from, std::deque<Step>& to, bool undoing);
    void enforceBudget();
    std::size_t budget_;
    std::optional<BrickMaskMap> open_;
    std::deque<Step> undo_, redo_;
    std::size_t bytes_ = 0, lastStrokeBytes_ = 0;
    std::uint64_t frame_ = 0;
};

}  // namespace curette::plan
