#pragma once
#include "tools/command_line.h"

namespace curette::bench {
// curette bench cao --scene S [--rays 6,14,26,54] [--meshes 1,2] [--frames N] [--json FILE]
int benchCao(const CommandLine& cl);
}  // namespace curette::bench
