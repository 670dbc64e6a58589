#pragma once
#include "tools/command_line.h"

namespace curette::bench {
// curette bench dos --scene S [--size WxH] [--frames N] [--reference-pixels N] [--json FILE]
int benchDos(const CommandLine& cl);
}  // namespace curette::bench
