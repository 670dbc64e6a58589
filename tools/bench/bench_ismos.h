#pragma once
#include "tools/command_line.h"

namespace curette::bench {
// curette bench ismos --scene S [--size WxH] [--frames N] [--reference-pixels N] [--reference-points N]
//                     [--json FILE]
int benchIsmos(const CommandLine& cl);
}  // namespace curette::bench
