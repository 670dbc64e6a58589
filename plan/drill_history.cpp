#include "plan/drill_history.h"

namespace curette::plan {

std::size_t DrillHistory::Step::bytes() const {
    return (before.size() + after.size()) * (sizeof(BrickMasks) + sizeof(std::uint32_t));
}

void DrillHistory::beginStroke() {
    if (!open_) open_.emplace();
}

void DrillHistory::endStroke(const RemovalVolume& removal) {
    if (!open_) return;
    Step step;
    step.before = std::move(*open_);
    open_.reset();
    if (step.before.empty()) return;
    for (const auto& entry : step.before) step.after[entry.first] = removal.brickMasks(entry.first);
    lastStrokeBytes_ = step.bytes();
    bytes_ += lastStrokeBytes_;
    for (const Step& s : redo_) bytes_ -= s.bytes();
    redo_.clear();
    undo_.push_back(std::move(step));
    enforceBudget();
}

bool DrillHistory::undo(RemovalVolume& removal) {
    endStroke(removal);
    if (undo_.empty()) return false;
    removal.setBricks(undo_.back().before);
    redo_.push_back(std::move(undo_.back()));
    undo_.pop_back();
    return true;
}

bool DrillHistory::redo(RemovalVolume& removal) {
    endStroke(removal);
    if (redo_.empty()) return false;
    removal.setBricks(redo_.back().after);
    undo_.push_back(std::move(redo_.back()));
    redo_.pop_back();
    return true;
}

void DrillHistory::enforceBudget() {
    while (bytes_ > budget_ && undo_.size() > 1) {
        bytes_ -= undo_.front().bytes();
        undo_.pop_front();
    }
}

}  // namespace curette::plan
