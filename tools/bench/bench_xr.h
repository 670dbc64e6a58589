#pragma once
#include "tools/command_line.h"

namespace curette::bench {
// curette bench xr [--scene S] [--test-runtime] [--size WxH] [--frames N] [--runs N] [--drill] [--json FILE]
int benchXr(const CommandLine& cl);
}  // namespace curette::bench
