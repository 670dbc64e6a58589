#pragma once
// The live distance from the selected tool to the nearest protected structure (plan/tool_clearance.h), for
// the side bar while a mesh moves: the removal report's margins follow only once the meshes are still. The
// distance transform of the protected structures is made once, on a thread of its own, so opening a scene
// does not wait for it. No GL call.

#include "session/interaction.h"
#include "session/loaded_scene.h"
#include "plan/tool_clearance.h"

#include <future>
#include <memory>
#include <optional>

namespace curette {

// Every protected label of every label set, on the scan grid (x fastest): 1 where a voxel is protected.
std::vector<std::uint8_t> protectedCells(const LoadedScene& loaded);

class ClearanceReadout {
public:
    explicit ClearanceReadout(const LoadedScene& loaded);
    // Whether the scene has a protected structure at all (nothing to show otherwise).
    bool applies() const { return applies_; }
    // The clearance of mesh `index` of `state` (recomputed only when its geometry, scale or pose changed);
    // nullopt while the distance transform is being made or when there is no such mesh.
    std::optional<plan::Clearance> of(const InteractionState& state, int index);

private:
    bool applies_ = false;
    std::shared_future<std::shared_ptr<const plan::ToolClearance>> clearance_;
    struct Key {
        const clip::TriangleMesh* geometry = nullptr;
        clip::RigidPose pose;
        glm::dvec3 scale{0.0};
        bool operator==(const Key&) const = default;
    };
    std::optional<Key> last_;
    std::optional<plan::Clearance> value_;
};

}  // namespace curette
