#pragma once
// Options of `bench cao` and `bench view`: the scene's LAO settings (both), and what the exact frame recasts (view;
// bench cao always casts every pixel).

#include "tools/command_line.h"
#include "render/model/lao_settings.h"

namespace curette::bench {

// --unseen-voxels skip|compute: whether steps I and V cast LAO rays from voxels no visible sample reads
// (LaoSettings::onlyWhereSeen; skip is the default and gives the same image).
OptionSpec unseenVoxelsOption();
void applyUnseenVoxelsOption(const CommandLine& cl, LaoSettings& lao);

// --recast changed|all: whether an exact frame after mesh motions casts only the pixels they can change
// (Renderer::setRecastOnlyChangedPixels; changed is the default and gives the same image).
OptionSpec recastOption();
bool recastOnlyChanged(const CommandLine& cl);

}  // namespace curette::bench
