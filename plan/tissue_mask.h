#pragma once
// Which voxels the report counts as tissue: a carve through air (a mesh poking out of the head, the gap
// between scalp and the scanner table) removes nothing. The default rule is what the user sees: a voxel is
// tissue when the transfer function's opacity at its own value (TF_o of CAO Algorithm 2, no gradient factor,
// no interpolation) is above a small threshold, 0.02 per TF unit length, which keeps every TF's visible
// ramps and drops the transparent background (noise in air stays below it under the presets). With a label
// set, tissue can instead be "inside these labels" (e.g. the brain mask); or every voxel counts.

#include "base/label_map.h"
#include "base/transfer_function.h"
#include "base/volume.h"
#include "plan/removal_field.h"

#include <cstdint>
#include <string>
#include <vector>

namespace curette::plan {

enum class TissueRule : std::uint8_t { Opacity, Labels, All };
const char* tissueRuleName(TissueRule rule);  // "opacity", "labels", "all"

struct ReportSettings {
    TissueRule tissue = TissueRule::Opacity;
    double opacityThreshold = 0.02;   // Opacity: tissue when TF opacity > this (per TF unit length)
    std::vector<int> tissueLabelIds;  // Labels: tissue when the first label set's id is one of these
};

// 1 for tissue, 0 otherwise, for the voxels of `box` (x fastest). `labels` is the first label set's map on
// the volume's grid; needed (else InputError) for TissueRule::Labels. Voxels without data are never tissue.
std::vector<std::uint8_t> tissueInBox(const VolumeData& volume, const TransferFunction& tf, const ReportSettings& settings,
                                      const LabelMap* labels, const VoxelBox& box);

// Under the opacity rule a shown label counts with the opacity it is drawn with: the renderer classifies a
// sample max(TF opacity, label opacity) with the label of the first set showing one there (shaders/labels.glsl,
// scene/scene_labels.h labelRendering). `shown` lists the sets in scene order, each with its opacity per id
// (0: not shown); a voxel becomes tissue where the first set showing its label gives more than the threshold.
struct ShownLabels {
    const LabelMap* labels = nullptr;
    const std::vector<double>* opacityById = nullptr;
};
void addShownLabels(std::vector<std::uint8_t>& tissue, const VoxelBox& box, const std::vector<ShownLabels>& shown, double threshold);

// A protected label is tissue whatever the rule and the TF: a carve into a structure the TF hides (a glass TF,
// a gyrus drawn by its label's style) still removes it and warns. Marks `labels`' voxels with one of
// `protectedIds` in `tissue` (over `box`, as tissueInBox made it).
void addProtectedLabels(std::vector<std::uint8_t>& tissue, const VoxelBox& box, const LabelMap& labels, const std::vector<int>& protectedIds);

}  // namespace curette::plan
