#pragma once
#include "tools/command_line.h"

namespace curette::bench {
// curette bench input [--reports N] [--frames N] [--json FILE]
int benchInput(const CommandLine& cl);
}  // namespace curette::bench
