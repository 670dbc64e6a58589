#pragma once
// Undo and redo of drill strokes. A stroke (drill control pressed .. released, over any number of frames) is
// one undo step, stored as brick-sparse differences: the masks of the bricks it changed, before and after
// (plan/removal_volume.h). The history is bounded by memory, not by a count: when the steps held exceed the
// budget the oldest are forgotten (the removal itself is kept).

#include "plan/removal_volume.h"

#include <cstddef>
#include <deque>
#include <optional>

namespace curette::plan {

inline constexpr std::size_t kDefaultUndoBudgetBytes = std::size_t(256) << 20;

class DrillHistory {
public:
    explicit DrillHistory(std::size_t budgetBytes = kDefaultUndoBudgetBytes) : budget_(budgetBytes) {}

    // A stroke: begin, then each frame's RemovalVolume::apply with before() as its record, then end. end()
    // makes it one undo step (when it changed anything) and clears the redo steps.
    void beginStroke();
    bool strokeOpen() const { return open_.has_value(); }
    BrickMaskMap* before() { return open_ ? &*open_ : nullptr; }
    void endStroke(const RemovalVolume& removal);

    // Undo / redo the last step; false when there is none. An open stroke is ended first.
    bool undo(RemovalVolume& removal);
    bool redo(RemovalVolume& removal);
    std::size_t undoSteps() const { return undo_.size(); }
    std::size_t redoSteps() const { return redo_.size(); }
    std::size_t bytes() const { return bytes_; }                 // held by every step
    std::size_t lastStrokeBytes() const { return lastStrokeBytes_; }
    std::size_t budgetBytes() const { return budget_; }

private:
    struct Step {
        BrickMaskMap before, after;
        std::size_t bytes() const;
    };
    void enforceBudget();
    std::size_t budget_;
    std::optional<BrickMaskMap> open_;
    std::deque<Step> undo_, redo_;
    std::size_t bytes_ = 0, lastStrokeBytes_ = 0;
};

}  // namespace curette::plan
