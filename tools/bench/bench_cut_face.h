#pragma once
#include "tools/command_line.h"

namespace curette::bench {
// curette bench cut-face [--scene S | --uniform] [--size WxH] [--frames N] [--json FILE]
int benchCutFace(const CommandLine& cl);
}  // namespace curette::bench
