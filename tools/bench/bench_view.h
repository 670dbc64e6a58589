#pragma once
#include "tools/command_line.h"

namespace curette::bench {
// curette bench view --session F [--size WxH] [--quality exact|adaptive] [--check] [--json FILE]: the viewer's
// frame loop (viewer/view_frame_loop.h) driven headless by a session played back in real time.
int benchView(const CommandLine& cl);
}  // namespace curette::bench
