#pragma once
// A head-mounted display's two located eyes as a file (`render --xr-views F`, docs/commands.md): the views
// an OpenXR runtime located for one frame, so a frame of `view --xr` can be rendered again headless. The
// test runtime (tests/xr_runtime) writes one per frame it captures:
//   {"space": "stage" | "local", "recommended_size": [W, H],
//    "views": [{"position_m": [x, y, z], "orientation": [x, y, z, w], "fov_rad": [left, right, up, down]}, {...}]}
// Each view may also carry "submitted_fov_rad" and "image_rect" (what the application submitted; not read).

#include "render/model/tracked_view.h"

#include <array>
#include <filesystem>

namespace curette {

struct TrackedViewsFile {
    RoomSpace space = RoomSpace::Stage;
    glm::ivec2 recommendedSize{0};
    std::array<TrackedView, 2> views{};   // left, right
};

// Throws InputError naming the file and key on bad input.
TrackedViewsFile readTrackedViews(const std::filesystem::path& path);

}  // namespace curette
