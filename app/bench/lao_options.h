#pragma once
// LAO options shared by `bench cao` and `bench view`, applied to the scene's LAO settings.

#include "app/command_line.h"
#include "render/lao_settings.h"

namespace curette::bench {

// --unseen-voxels skip|compute: whether steps I and V cast LAO rays from voxels no visible sample reads
// (LaoSettings::onlyWhereSeen; skip is the default and gives the same image).
OptionSpec unseenVoxelsOption();
void applyUnseenVoxelsOption(const CommandLine& cl, LaoSettings& lao);

}  // namespace curette::bench
