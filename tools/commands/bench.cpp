// curette bench <what> --scene S: speed (and error next to it) of one part of the pipeline. Tests assert
// results; benches report numbers, as a table and as JSON.
#include "tools/bench/bench_cao.h"
#include "tools/bench/bench_cut_face.h"
#include "tools/bench/bench_dos.h"
#include "tools/bench/bench_input.h"
#include "tools/bench/bench_ismos.h"
#include "tools/bench/bench_raycast.h"
#include "tools/bench/bench_report.h"
#include "tools/bench/bench_stereo.h"
#include "tools/bench/bench_view.h"
#include "tools/bench/bench_drill.h"
#include "tools/bench/bench_tracts.h"
#include "tools/bench/bench_xr.h"
#include "tools/bench/lao_options.h"
#include "tools/command_line.h"
#include "tools/commands/commands.h"

namespace curette::commands {

std::vector<Command> benchCommands() {
    return {
        {{"bench raycast", "--scene S", "the ray caster's speed per configuration, with its error against the CPU reference next to it",
          withGpuOption({{"scene", true, "scene file"},
                {"size", true, "image size (default 512x512)", "WxH"},
                {"frames", true, "frames measured per configuration (default 8)"},
                {"reference-pixels", true, "pixels checked against the CPU reference (default 48)"},
                {"json", true, "JSON output file (default bench-raycast.json)"}})},
         &bench::benchRaycast},
        {{"bench cao", "--scene S", "CAO against LAO over moving spheres: speed per ray count and mesh count, and the error against 512-ray LAO",
          withGpuOption({{"scene", true, "scene file (its volume, TF and LAO settings; the bench adds the spheres)"},
                {"rays", true, "LAO ray counts K, e.g. 6,14,26,54 (default)"},
                {"meshes", true, "mesh counts to measure, 1 and/or 2 (default 1,2)"},
                {"frames", true, "frames per configuration (default 3)"},
                {"size", true, "image size (default 512x512)", "WxH"},
                {"ground-truth-voxels", true, "voxels checked against 512-ray LAO (default 400)"},
                {"compare-dispatch", false, "compare step V variants at every K (default: K = 26 only)"},
                {"depth-box-tests", true, "on (default) or off: the ray caster and step IV test every sample against every mesh"},
                {"second-mesh", true, "moves (default: with the first, as in the paper) or still (stays where it overlaps the first at the start)"},
                bench::unseenVoxelsOption(),
                {"json", true, "JSON output file (default bench-cao.json)"}})},
         &bench::benchCao},
        {{"bench dos", "--scene S", "directional occlusion shading with tubes: speed, and the error against a Monte-Carlo reference",
          withGpuOption({{"scene", true, "scene file with tubes (e.g. assets/scenes/fibers.json)"},
                {"size", true, "image size (default 384x384)", "WxH"},
                {"frames", true, "frames per configuration (default 3)"},
                {"reference-pixels", true, "pixels checked against the Monte-Carlo reference (default 24)"},
                {"reference-directions", true, "cone directions of the reference (default 48)"},
                {"json", true, "JSON output file (default bench-dos.json)"}})},
         &bench::benchDos},
        {{"bench ismos", "--scene S", "ISMOS (soft shadows of area lights): speed, and the error against the physical reference",
          withGpuOption({{"scene", true, "scene file (its volume, TF, lights and ISMOS settings)"},
                {"size", true, "image size (default 256x256)", "WxH"},
                {"frames", true, "frames per configuration (default 3)"},
                {"reference-pixels", true, "pixels checked against the physical reference (default 150)"},
                {"reference-points", true, "stratified points per light disk of the reference (default 64)"},
                {"json", true, "JSON output file (default bench-ismos.json)"}})},
         &bench::benchIsmos},
        {{"bench cut-face", "[--scene S | --uniform]", "how rough the cut face of a carve looks in each shading mode, cut-face rules off and on, next to the time per frame",
          withGpuOption({{"scene", true, "scene file with a clip mesh (default assets/scenes/head-cut-face.json)"},
                {"uniform", false, "a box of homogeneous tissue carved by a sphere instead of a scene"},
                {"size", true, "image size (default 384x384)", "WxH"},
                {"frames", true, "frames timed per configuration (default 3)"},
                {"images", true, "folder to write each configuration's image to (PNG)"},
                {"normal-depth", true, "mm behind the face lit by its normal (default: the scene's)"},
                {"normal-opacity", true, "opacity behind the face over which its normal fades (default: the scene's)"},
                {"modes", true, "shading modes to measure, comma-separated (default all; solid always runs: the others are measured against it)"},
                {"json", true, "JSON output file (default bench-cut-face.json)"}})},
         &bench::benchCutFace},
        {{"bench input", "", "report parsing throughput and report-to-pose latency",
          {{"reports", true, "random reports per device family (default 20000)"},
                {"frames", true, "frames of the latency measurement (default 20000)"},
                {"json", true, "JSON output file (default bench-input.json)"}}},
         &bench::benchInput},
        {{"bench report", "--scene S", "the removal report's time per stage, and its GPU inputs against the CPU oracle",
          withGpuOption({{"scene", true, "scene file with clip meshes (labels and tubes are reported too)"},
                {"repeats", true, "reports measured, each with the meshes moved 0.5 mm (default 8)"},
                {"oracle-voxels", true, "voxels checked against the CPU winding-number oracle (default 1500)"},
                {"json", true, "JSON output file (default bench-report.json)"}})},
         &bench::benchReport},
        {{"bench stereo", "--scene S", "per shading mode, how alike the two eyes shade one surface point",
          withGpuOption({{"scene", true, "scene file (its first frame is the pair's centre)"},
                {"size", true, "image size of each eye (default 256x256)", "WxH"},
                {"eye-separation", true, "eye separation in mm (default 65)"},
                {"stride", true, "left-eye pixels tried: every Nth column and row (default 2)"},
                {"depth-tolerance", true, "how far apart the eyes' surface points may be, mm (default 2 ray steps)"},
                {"modes", true, "shading modes to compare (default solid,phong,lao,cao,dos,ismos)"},
                {"json", true, "JSON output file (default bench-stereo.json)"}})},
         &bench::benchStereo},
        {{"bench view", "--session F", "the viewer's frame loop driven headless by a session played back in real time",
          withGpuOption({{"session", true, "session file (JSON Lines) played back in real time"},
                {"size", true, "window size WxH (default 1024x768)", "WxH"},
                {"quality", true, "exact|adaptive (default: adaptive on a software renderer, exact on a GPU)", "exact|adaptive"},
                {"settle", true, "seconds without motion after which the motion counts as stopped (default 0.1)"},
                {"precompute-budget", true, "ms of step I per frame while it runs (default 60)"},
                {"exact-budget", true, "adaptive quality: ms of the exact frame per frame, in slices (default 60; 0: whole)"},
                {"preview-target", true, "ms a motion preview is steered to (default 70)"},
                {"check", false, "also render the last state in a fresh renderer and compare image hashes"},
                {"rays", true, "LAO ray count K instead of the scene's (6, 14, 26, 54 or any fibonacci count)"},
                bench::unseenVoxelsOption(),
                bench::recastOption(),
                {"json", true, "JSON output file (default bench-view.json)"}})},
         &bench::benchView},
        {{"bench drill", "[--scene S]", "drilling: sweep steps per second, bricks and undo bytes per step, capsule error; exact frame after a stroke",
          withGpuOption({{"scene", true, "scene file (default assets/scenes/head-drill.json)"},
                {"size", true, "image size of the exact frames (default: the scene's)", "WxH"},
                {"json", true, "JSON output file (default bench-drill.json)"}})},
         &bench::benchDrill},
        {{"bench tracts", "[--scene S]", "lines and tubes at whole-brain scale: build, upload, GPU memory, frame time",
          withGpuOption({{"scene", true, "scene file with tubes (default assets/scenes/tracts-100k.json)"},
                {"counts", true, "streamline counts, the first N of each tube entry (default 1000,10000,100000)"},
                {"size", true, "image size (default 512x512)", "WxH"},
                {"frames", true, "frames timed per configuration and mode (default 3)"},
                {"modes", true, "shading modes timed (default phong,dos)"},
                {"geometries", true, "which of lines,cpu,gpu,impostor to measure (default all; impostor errors need cpu)"},
                {"million", true, "also a tractogram of about a million streamlines (.tck, .trk, .trx), first: load time, peak memory, impostor GPU bytes, one frame per mode", "FILE"},
                {"images", true, "folder to write each configuration's first frame to (PNG)"},
                {"json", true, "JSON output file (default bench-tracts.json)"}})},
         &bench::benchTracts},
        {{"bench xr", "[--scene S] [--test-runtime]", "a head-mounted display session: time per eye at the recommended size, CAO per frame, first frame, CAO == LAO",
          {{"scene", true, "scene file (default assets/scenes/head-carved.json: two tools)"},
           {"test-runtime", false, "curette's scripted OpenXR test runtime (tests/xr_runtime) instead of the active runtime; needs a display (xvfb-run)"},
           {"size", true, "with --test-runtime: the eye size the runtime recommends (default 160x144)", "WxH"},
           {"frames", true, "frames per run (default 6; the first runs step I)"},
           {"runs", true, "runs, each with a fresh renderer (default 3)"},
           {"drill", false, "with --test-runtime: the right trigger drills with its tool"},
           {"quality", true, "exact: both eyes exact every frame; adaptive: previews while the hands move, then (the script holding still) the exact frame in slices (default: adaptive on a software renderer, exact on a GPU)", "exact|adaptive"},
           {"json", true, "JSON output file (default bench-xr.json)"}}},
         &bench::benchXr},
    };
}

}  // namespace curette::commands
