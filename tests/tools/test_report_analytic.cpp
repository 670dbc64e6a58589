// `curette report`'s figures on cases whose answers are known (tools/bench/report_analytic.h): removed
// volumes within 0.5 % of the meshes' exact volumes, margins within 0.25 mm of the gap and within their
// stated uncertainty, and contact only when something of the wall is removed.
#include "tools/bench/report_analytic.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace curette::bench {
namespace {

TEST(ReportAnalytic, VolumesWithinHalfAPercentAndMarginsWithinAQuarterMillimetre) {
    auto context = gl::createHeadlessContext();
    const std::vector<AnalyticCase> cases = analyticReportCases(*context);
    ASSERT_GT(cases.size(), 40u);
    for (const AnalyticCase& c : cases) {
        std::printf("[ analytic ] %-6s %-17s %-22s exact %9.4f reported %9.4f +- %.4f\n", c.kind.c_str(), c.grid.c_str(), c.name.c_str(),
                    c.exact, c.reported, c.uncertainty);
        if (c.kind == "volume") {
            EXPECT_LT(std::abs(c.error()) / c.exact, 0.005) << c.grid << " " << c.name;
            EXPECT_LE(std::abs(c.error()), c.uncertainty) << c.grid << " " << c.name << ": within the stated uncertainty";
        } else {
            EXPECT_FALSE(c.wallTouched) << c.name << ": nothing of the wall is removed";
            EXPECT_NEAR(c.reported, c.exact, 0.25) << c.name;
            EXPECT_LE(std::abs(c.error()), std::max(c.uncertainty, 1e-9)) << c.name << ": within the stated uncertainty";
        }
    }
}

}  // namespace
}  // namespace curette::bench
