#pragma once
#include "tools/command_line.h"

namespace curette::bench {
// curette bench report --scene S [--repeats N] [--oracle-voxels N] [--json FILE]
int benchReport(const CommandLine& cl);
}  // namespace curette::bench
