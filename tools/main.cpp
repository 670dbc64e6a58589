// curette: carve CT and MRI volumes with exact ambient occlusion. See README.md.
#include "tools/commands/commands.h"
#include "base/error.h"
#include "base/log.h"

#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

namespace {

const char* kUsage =
    "usage: curette <command> [options]\n"
    "\n"
    "commands:\n"
    "  info FILE                        what a volume file holds: dimensions, spacing, affine, type,\n"
    "                                   value range, histogram\n"
    "  render --scene S --out F.png     render one frame headless (EGL) and write a PNG\n"
    "         [--size WxH] [--shading MODE] [--azimuth DEG] [--elevation DEG] [--timings]\n"
    "         [--stereo side-by-side|anaglyph] [--eye-separation MM]\n"
    "         [--turntable N --out DIR [--fps F]]  N frames around the vertical axis, and an MP4 (ffmpeg)\n"
    "  view --scene S                   interactive viewer: devices, keyboard, F9 records a session\n"
    "         [--mapping F.json] [--record F.jsonl] [--no-devices]\n"
    "  record --scene S --out F.jsonl --synthetic DEVICES\n"
    "                                   record a session headless from scripted devices\n"
    "         [--frames N] [--fps F] [--report-hz F] [--seed N] [--mapping F] [--unplug FRAME]\n"
    "  replay F.jsonl                   re-render a session headless, frame by frame\n"
    "         [--out DIR] [--every N] [--check] [--from-reports] [--no-render] [--lenient] [--size WxH]\n"
    "         [--report]                 with --out: the removal report every Nth frame, removal.csv/.png\n"
    "         [--mp4]                    with --out: replay.mp4 of the frames (ffmpeg)\n"
    "  report --scene S --out DIR       what the carve removes (mL, per structure, per tract bundle, margins)\n"
    "         [--session F --frame N] [--lps] [--no-exports]\n"
    "                                   and the plan's exports: labelmap (.nii.gz, .seg.nrrd), cavity\n"
    "                                   surface (STL, glTF), plan scene, cut and spared tracts (.tck)\n"
    "  bench raycast|cao|dos|ismos --scene S  speed with the error against the CPU reference next to it\n"
    "  bench tracts [--scene S] [--counts 1000,10000,100000]\n"
    "                                   lines and tubes at whole-brain scale: build, upload, GPU memory, frame time\n"
    "  tracts synth --from DIR --count N --out F.tck\n"
    "                                   jittered copies of tract bundles (deterministic: --seed, --jitter MM)\n"
    "  bench input                      report parsing throughput and report-to-pose latency\n"
    "  bench report --scene S           the removal report's time per stage, and its GPU inputs vs the CPU oracle\n"
    "  bench stereo --scene S           per shading mode, how alike the two eyes shade one surface point\n"
    "  info --gl                        the EGL devices and platforms, and the GL context headless commands get\n"
    "\n"
    "shading modes: solid, phong, lao, cao, dos, ismos\n"
    "every headless command (render, replay, report, bench) takes --gpu N|llvmpipe|surfaceless\n"
    "exit codes: 0 success, 2 bad input (the message names file, field and expected form),\n"
    "            3 system problem (GL driver, disk), 1 a failed check or anything else\n";

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "help")) {
        std::fputs(kUsage, argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    std::string command = argv[1];
    curette::commands::Arguments args(argv + 2, argv + argc);
    try {
        if (command == "info") return curette::commands::info(args);
        if (command == "render") return curette::commands::render(args);
        if (command == "view") return curette::commands::view(args);
        if (command == "bench") return curette::commands::bench(args);
        if (command == "record") return curette::commands::record(args);
        if (command == "replay") return curette::commands::replay(args);
        if (command == "report") return curette::commands::report(args);
        if (command == "tracts") return curette::commands::tracts(args);
        std::fprintf(stderr, "curette: unknown command \"%s\"\n\n%s", command.c_str(), kUsage);
        return 2;
    } catch (const curette::InputError& e) {
        std::fprintf(stderr, "curette %s: error: %s\n", command.c_str(), e.what());
        return 2;
    } catch (const curette::SystemError& e) {
        std::fprintf(stderr, "curette %s: error: %s\n", command.c_str(), e.what());
        return 3;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "curette %s: internal error: %s\n", command.c_str(), e.what());
        return 1;
    }
}
