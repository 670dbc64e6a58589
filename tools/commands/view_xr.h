#pragma once
// `curette view --xr`: the scene in a head-mounted display through OpenXR (tools/commands/view_xr.cpp).

#include "tools/command_line.h"

namespace curette::commands {

int viewXr(const CommandLine& cl);

}  // namespace curette::commands
