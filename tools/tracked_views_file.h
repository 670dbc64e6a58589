#pragma once
// A head-mounted display's two located eyes as a file (`render --xr-views F`, docs/commands.md): the views
// an OpenXR runtime located for one frame, so a frame of `view --xr` can be rendered again headless. The
// test runtime (tests/xr_runtime) writes one per frame it captures:
//   {"space": "stage" | "local", "recommended_size": [W, H],
//    "views": [{"position_m": [x, y, z], "orientation": [x, y, z, w], "fov_rad": [left, right, up, down]}, {...}]}
// Each view may also carry "submitted_fov_rad" and "image_rect" (what the application submitted; not read).
// "volume": {"centre_m": [x, y, z], "turn": [x, y, z, w], "scale": s (optional, 1)} places a volume a hand moved (RoomAnchor; absent: on
// its table); `view --xr --save-views` writes it, and a test adds a recorded session's.

#include "render/model/tracked_view.h"

#include <array>
#include <filesystem>
#include <optional>

namespace curette {

struct TrackedViewsFile {
    RoomSpace space = RoomSpace::Stage;
    glm::ivec2 recommendedSize{0};
    std::array<TrackedView, 2> views{};   // left, right
    std::optional<glm::dvec3> volumeCentreRoomM;   // with volumeTurnRoom: where a hand left the volume
    glm::dquat volumeTurnRoom{1.0, 0.0, 0.0, 0.0};
    double volumeScale = 1.0;                      // "scale" (optional): two hands scaled it (RoomAnchor::volumeScale)
};

// The anchor of `file`'s frame: the table's, moved where the file says.
RoomAnchor viewsAnchor(const TrackedViewsFile& file, const VolumeGeometry& geometry);

// Throws InputError naming the file and key on bad input.
TrackedViewsFile readTrackedViews(const std::filesystem::path& path);

}  // namespace curette
