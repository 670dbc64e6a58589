#pragma once
// A scene's label volumes, loaded: each set read (io/), its table completed, resampled onto the scan
// grid by nearest label (base/label_map.h), and the ids and names the scene wrote (protected, shown, the
// report's tissue labels) resolved against the table. Also the one mapping from the sets to what the
// renderer draws (render/label_overlay.h): all sets in one id space, set s's id n at offset_s + n.

#include "scene/scene.h"
#include "base/label_map.h"
#include "base/volume.h"

#include <glm/glm.hpp>

#include <vector>

namespace curette {

struct LoadedLabelSet {
    std::string name;
    std::string source;                 // the label volume's file
    // The files read, for a report's checksums: the label volume's (VolumeData::files), the table (given, or
    // found beside the volume) and the colours.
    std::vector<std::filesystem::path> volumeFiles;
    std::optional<std::filesystem::path> tableFile, colorsFile;
    LabelTable table;                   // every id of the volume has an entry (generated where the file has none)
    LabelMap onScanGrid;                // resampled onto the scan's grid
    std::vector<int> protectedIds;
    std::vector<bool> shown;            // by id
    double opacity = 0.5;
};

std::vector<LoadedLabelSet> loadSceneLabels(const Scene& scene, const VolumeData& scan);

// Resolves ids or names (as the scene wrote them) against a table; `field` is the scene key for messages.
std::vector<int> resolveLabelIds(const std::vector<std::string>& idsOrNames, const LabelTable& table,
                                 const std::string& sceneFile, const std::string& field);

// What the renderer draws: one id per scan voxel (the first set, in scene order, with a shown label there)
// and a style per combined id (rgb, opacity per unit length; 0 where not shown). Empty ids when no label of
// any set is shown: the scene then compiles no label code.
struct LabelRendering {
    std::vector<std::uint16_t> ids;
    std::vector<glm::vec4> styles;
};
LabelRendering labelRendering(const std::vector<LoadedLabelSet>& sets);

}  // namespace curette
