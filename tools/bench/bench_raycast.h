#pragma once
#include "tools/command_line.h"

namespace curette::bench {
// curette bench raycast --scene S [--size WxH] [--frames N] [--reference-pixels N] [--json FILE]
int benchRaycast(const CommandLine& cl);
}  // namespace curette::bench
