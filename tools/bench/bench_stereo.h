#pragma once
#include "tools/command_line.h"

namespace curette::bench {
// curette bench stereo --scene S [--size WxH] [--eye-separation MM] [--stride N] [--depth-tolerance MM]
//                               [--modes LIST] [--json FILE]
int benchStereo(const CommandLine& cl);
}  // namespace curette::bench
