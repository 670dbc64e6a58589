#pragma once
// The removal report on cases whose answers are known, computed as `curette report` computes them (the
// renderer's clip maps, the removal field at the report's N, the report with its margins refined through the
// same clip test):
//   volume  meshes on uniform opaque scans against the meshes' exact volumes: boxes from 5 to 100 mm, a
//           sphere, a cylinder, a capsule and a torus, aligned and turned, on a 1 mm grid and a CT-like
//           0.5 x 0.5 x 3 mm one tilted 17 degrees, and a box partly outside the scan;
//   margin  a protected wall of voxels (i >= 32; its face at x = 31.5 on a grid with centres on integers)
//           beside boxes and a sphere at known gaps, from touching (0 mm, nothing removed) to 4 mm.
// `bench report` prints them beside its timings; tests/tools asserts the targets on them.

#include "gl/context.h"

#include <string>
#include <vector>

namespace curette::bench {

struct AnalyticCase {
    std::string kind;         // "volume" (mL) or "margin" (mm)
    std::string grid, name;
    double exact = 0, reported = 0, uncertainty = 0;
    double atImageSamples = 0; // volume cases: mL removed at the image's N (step IV's, LaoSettings), not the report's
    bool wallTouched = false;  // margin cases: the report says the wall was touched (a warning)
    double ms = 0;             // the field and the report
    double error() const { return reported - exact; }
};

std::vector<AnalyticCase> analyticReportCases(gl::Context& context);

}  // namespace curette::bench
