#pragma once
#include "tools/command_line.h"

namespace curette::bench {
// curette bench drill [--scene S] [--size WxH] [--json FILE]
int benchDrill(const CommandLine& cl);
}  // namespace curette::bench
