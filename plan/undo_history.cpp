#include "plan/undo_history.h"

namespace curette::plan {

void UndoHistory::beginStroke() {
    if (!open_) open_.emplace();
}

void UndoHistory::push(Step step) {
    bytes_ += step.bytes;
    for (const Step& s : redo_) bytes_ -= s.bytes;
    redo_.clear();
    undo_.push_back(std::move(step));
    enforceBudget();
}

void UndoHistory::endStroke(const RemovalVolume& removal) {
    if (!open_) return;
    Step step;
    step.before = std::move(*open_);
    open_.reset();
    if (step.before.empty()) return;
    for (const auto& entry : step.before) step.after[entry.first] = removal.brickMasks(entry.first);
    step.bytes = (step.before.size() + step.after.size()) * (sizeof(BrickMasks) + sizeof(std::uint32_t));
    lastStrokeBytes_ = step.bytes;
    push(std::move(step));
}

void UndoHistory::pushEdit(const RemovalVolume& removal, nlohmann::json undoEdits, nlohmann::json redoEdits, const std::string& mergeKey) {
    endStroke(removal);
    auto size = [](const Step& s) { return sizeof(Step) + s.undoEdits.dump().size() + s.redoEdits.dump().size(); };
    if (!mergeKey.empty() && redo_.empty() && !undo_.empty() && undo_.back().mergeKey == mergeKey && undo_.back().frame + 1 == frame_) {
        Step& last = undo_.back();   // the same drag: its undo stays, this redo replaces its own
        bytes_ -= last.bytes;
        last.redoEdits = std::move(redoEdits);
        last.frame = frame_;
        last.bytes = size(last);
        bytes_ += last.bytes;
        enforceBudget();
        return;
    }
    Step step;
    step.undoEdits = std::move(undoEdits);
    step.redoEdits = std::move(redoEdits);
    step.mergeKey = mergeKey;
    step.frame = frame_;
    step.bytes = size(step);
    push(std::move(step));
}

UndoResult UndoHistory::moveLast(RemovalVolume& removal, std::deque<Step>& from, std::deque<Step>& to, bool undoing) {
    endStroke(removal);
    if (from.empty()) return {};
    Step& step = from.back();
    UndoResult result{true, undoing ? step.undoEdits : step.redoEdits};
    if (result.edits.is_null()) removal.setBricks(undoing ? step.before : step.after);   // a stroke
    to.push_back(std::move(step));
    from.pop_back();
    return result;
}

UndoResult UndoHistory::undo(RemovalVolume& removal) { return moveLast(removal, undo_, redo_, true); }

UndoResult UndoHistory::redo(RemovalVolume& removal) { return moveLast(removal, redo_, undo_, false); }

void UndoHistory::enforceBudget() {
    while (bytes_ > budget_ && undo_.size() > 1) {
        bytes_ -= undo_.front().bytes;
        undo_.pop_front();
    }
}

}  // namespace curette::plan
