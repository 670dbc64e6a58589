#include "plan/tissue_mask.h"

#include "base/error.h"

#include <algorithm>
#include <string>

namespace curette::plan {

const char* tissueRuleName(TissueRule rule) {
    switch (rule) {
        case TissueRule::Opacity: return "opacity";
        case TissueRule::Labels: return "labels";
        case TissueRule::All: return "all";
    }
    return "?";
}

std::vector<std::uint8_t> tissueInBox(const VolumeData& volume, const TransferFunction& tf, const ReportSettings& settings,
                                      const LabelMap* labels, const VoxelBox& box) {
    std::vector<std::uint8_t> tissue(box.voxelCount(), 0);
    if (settings.tissue == TissueRule::Labels) {
        if (!labels) throw InputError("<report settings>", "tissue", "a label set for the \"labels\" tissue rule");
        if (labels->dims != volume.dims)
            throw InputError(labels->source, "dims", "the scan's grid (resample the labels first)");
    }
    std::vector<bool> tissueIds;
    if (settings.tissue == TissueRule::Labels) {
        tissueIds.assign(65536, false);
        for (int id : settings.tissueLabelIds)
            if (id >= 0 && id < 65536) tissueIds[static_cast<std::size_t>(id)] = true;
    }
    std::size_t at = 0;
    for (int k = box.origin.z; k < box.origin.z + box.size.z; ++k)
        for (int j = box.origin.y; j < box.origin.y + box.size.y; ++j)
            for (int i = box.origin.x; i < box.origin.x + box.size.x; ++i, ++at) {
                const std::size_t index = volume.linearIndex(i, j, k);
                switch (settings.tissue) {
                    case TissueRule::All: tissue[at] = 1; break;
                    case TissueRule::Labels: tissue[at] = tissueIds[labels->ids[index]] ? 1 : 0; break;
                    case TissueRule::Opacity:
                        if (volume.isNoData(index)) break;
                        tissue[at] = tf.evaluateOpacity(volume.valueScale * volume.normalized(index) + volume.valueOffset) >
                                             settings.opacityThreshold ? 1 : 0;
                        break;
                }
            }
    return tissue;
}

void addShownLabels(std::vector<std::uint8_t>& tissue, const VoxelBox& box, const std::vector<ShownLabels>& shown, double threshold) {
    if (shown.empty()) return;
    std::size_t at = 0;
    for (int k = box.origin.z; k < box.origin.z + box.size.z; ++k)
        for (int j = box.origin.y; j < box.origin.y + box.size.y; ++j)
            for (int i = box.origin.x; i < box.origin.x + box.size.x; ++i, ++at)
                for (const ShownLabels& set : shown) {
                    const std::uint16_t id = set.labels->ids[set.labels->linearIndex(i, j, k)];
                    const double opacity = id < set.opacityById->size() ? (*set.opacityById)[id] : 0.0;
                    if (opacity <= 0.0) continue;   // not shown here: the next set may show one
                    if (opacity > threshold) tissue[at] = 1;
                    break;
                }
}

void addProtectedLabels(std::vector<std::uint8_t>& tissue, const VoxelBox& box, const LabelMap& labels, const std::vector<int>& protectedIds) {
    if (protectedIds.empty()) return;
    std::vector<bool> isProtected(65536, false);
    for (int id : protectedIds)
        if (id >= 0 && id < 65536) isProtected[static_cast<std::size_t>(id)] = true;
    std::size_t at = 0;
    for (int k = box.origin.z; k < box.origin.z + box.size.z; ++k)
        for (int j = box.origin.y; j < box.origin.y + box.size.y; ++j)
            for (int i = box.origin.x; i < box.origin.x + box.size.x; ++i, ++at)
                if (isProtected[labels.ids[labels.linearIndex(i, j, k)]]) tissue[at] = 1;
}

}  // namespace curette::plan
