#include "viewer/clearance_readout.h"

#include <algorithm>
#include <chrono>

namespace curette {

std::vector<std::uint8_t> protectedCells(const LoadedScene& loaded) {
    std::vector<std::uint8_t> cells;
    for (const LoadedLabelSet& set : loaded.labels) {
        if (set.protectedIds.empty()) continue;
        if (cells.empty()) cells.assign(set.onScanGrid.ids.size(), 0);
        for (std::size_t i = 0; i < set.onScanGrid.ids.size(); ++i)
            if (std::find(set.protectedIds.begin(), set.protectedIds.end(), set.onScanGrid.ids[i]) != set.protectedIds.end()) cells[i] = 1;
    }
    return cells;
}

ClearanceReadout::ClearanceReadout(const LoadedScene& loaded) {
    std::vector<std::uint8_t> cells = protectedCells(loaded);
    applies_ = std::find(cells.begin(), cells.end(), 1) != cells.end();
    if (!applies_) return;
    const glm::ivec3 dims = loaded.volume.dims;
    const glm::dmat4 indexToWorld = loaded.volume.indexToWorld;
    clearance_ = std::async(std::launch::async, [dims, indexToWorld, cells = std::move(cells)] {
                     return std::make_shared<const plan::ToolClearance>(dims, indexToWorld, cells);
                 }).share();
}

std::optional<plan::Clearance> ClearanceReadout::of(const InteractionState& state, int index) {
    if (!applies_ || index < 0 || index >= static_cast<int>(state.meshes.size())) return std::nullopt;
    if (clearance_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return std::nullopt;
    const MeshState& mesh = state.meshes[static_cast<std::size_t>(index)];
    Key key{mesh.geometry.get(), mesh.pose, mesh.scale};
    if (last_ != key) {
        value_ = clearance_.get()->of({mesh.geometry, mesh.pose, mesh.scale});
        last_ = key;
    }
    return value_;
}

}  // namespace curette
