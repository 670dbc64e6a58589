#pragma once
#include "tools/command_line.h"

namespace curette::bench {
// curette bench tracts [--scene S] [--counts 1000,10000,100000] [--size WxH] [--frames N] [--modes phong,dos]
//                      [--geometries lines,cpu,gpu,impostor] [--million FILE] [--images DIR] [--json FILE]
int benchTracts(const CommandLine& cl);
}  // namespace curette::bench
