// The frame plan (render/model/frame_plan.h), the descriptor tables and the checked shader interfaces.
#include "base/error.h"
#include "gl/program.h"
#include "render/model/frame.h"
#include "render/model/frame_plan.h"
#include "render/model/gpu_resources.h"
#include "render/renderer.h"
#include "render/model/shading_mode.h"
#include "tests/render/gl_test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace curette {
namespace {

std::vector<Pass> passes(const FramePlan& plan) {
    std::vector<Pass> out;
    for (const PlannedPass& p : plan.passes) out.push_back(p.pass);
    return out;
}

// The viewer shows the DOS settings when this says the slab pass runs; it must say what planFrame does.
TEST(FramePlan, SlabPassRunsAsThePlanSays) {
    EXPECT_TRUE(slabPassRuns(ShadingMode::Dos, false));
    EXPECT_FALSE(slabPassRuns(ShadingMode::Phong, false));
    EXPECT_FALSE(slabPassRuns(ShadingMode::Phong, true));    // tubes: G-buffer, then the ray cast
    EXPECT_TRUE(slabPassRuns(ShadingMode::Dos, true));       // tubes in dos: G-buffer, slab pass, composite
    EXPECT_FALSE(slabPassRuns(ShadingMode::Ismos, true));    // ISMOS shades the tubes itself
    for (const ShadingModeTraits& t : allShadingModes())
        for (bool tubes : {false, true}) {
            PlanInputs in;
            in.shading = t.mode;
            in.clipMeshes = 1;
            in.clipMapsCurrent = false;
            in.tubes = in.tubesInView = tubes;
            EXPECT_EQ(slabPassRuns(t.mode, tubes), planFrame(in).runs(Pass::SlabPass)) << t.name << (tubes ? " with tubes" : "");
        }
}

TEST(FramePlan, AStillSceneCostsStepSixAlone) {
    PlanInputs in;
    in.shading = ShadingMode::Cao;
    in.clipMeshes = 1;
    in.clipMapsCurrent = true;
    in.precomputedCurrent = true;
    in.ambientCurrent = true;
    EXPECT_EQ(passes(planFrame(in)), std::vector<Pass>{Pass::RayCast});
}

// Phong on a scan with a gradient volume builds it once, first, and its ray cast reads it; no other mode does.
TEST(FramePlan, OnlyPhongBuildsAndReadsTheGradientVolume) {
    PlanInputs in;
    in.shading = ShadingMode::Phong;
    in.gradientVolume = true;
    FramePlan first = planFrame(in);
    EXPECT_EQ(passes(first), (std::vector<Pass>{Pass::GradientVolume, Pass::RayCast}));
    EXPECT_TRUE(first.reads(Pass::RayCast, Resource::GradientVolume));
    in.gradientVolumeCurrent = true;
    EXPECT_EQ(passes(planFrame(in)), std::vector<Pass>{Pass::RayCast});
    EXPECT_TRUE(planFrame(in).reads(Pass::RayCast, Resource::GradientVolume));
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Cao, ShadingMode::Dos, ShadingMode::Ismos}) {
        in.shading = mode;
        in.gradientVolumeCurrent = false;
        FramePlan plan = planFrame(in);
        EXPECT_FALSE(plan.runs(Pass::GradientVolume)) << shadingModeName(mode);
        EXPECT_FALSE(plan.reads(Pass::RayCast, Resource::GradientVolume)) << shadingModeName(mode);
    }
    in.shading = ShadingMode::Phong;
    in.gradientVolume = false;   // a scan without one (16-bit, float, folded, no data)
    EXPECT_EQ(passes(planFrame(in)), std::vector<Pass>{Pass::RayCast});
    EXPECT_FALSE(planFrame(in).reads(Pass::RayCast, Resource::GradientVolume));
}

TEST(FramePlan, AmbientOcclusionPassesRunOnlyWhenTheirInputsChanged) {
    PlanInputs in;
    in.shading = ShadingMode::Cao;
    in.clipMeshes = 2;
    in.clipMapsCurrent = false;
    EXPECT_EQ(passes(planFrame(in)), (std::vector<Pass>{Pass::ClipMaps, Pass::LaoPrecompute, Pass::VoxelClipping, Pass::LaoRecompute,
                                                        Pass::RayCast}));
    in.clipMapsCurrent = true;
    in.precomputedCurrent = true;   // a pose moved: IV and V only
    EXPECT_EQ(passes(planFrame(in)), (std::vector<Pass>{Pass::VoxelClipping, Pass::LaoRecompute, Pass::RayCast}));
    in.shading = ShadingMode::Phong;  // no AO in phong, whatever is stale
    EXPECT_EQ(passes(planFrame(in)), std::vector<Pass>{Pass::RayCast});
}

// Tubes in view cost the ray caster's price in every mode without occlusion to propagate slice by slice: the
// G-buffer, then the ray cast, which ends each ray at the tube and shades it (its line reads the G-buffer). Only
// dos, whose combined occlusion is the model, keeps seed 000's slab pass and compositor.
TEST(FramePlan, TubesInViewGoThroughTheGBufferAndTheRayCastButInDos) {
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong, ShadingMode::Lao, ShadingMode::Cao}) {
        SCOPED_TRACE(shadingModeName(mode));
        PlanInputs in;
        in.shading = mode;
        in.tubes = true;
        in.tubesInView = true;
        in.precomputedCurrent = in.ambientCurrent = true;
        FramePlan plan = planFrame(in);
        ASSERT_EQ(passes(plan), (std::vector<Pass>{Pass::TubeGBuffer, Pass::RayCast}));
        const std::vector<Resource>& reads = plan.passes[1].reads;
        EXPECT_NE(std::find(reads.begin(), reads.end(), Resource::GBuffer), reads.end()) << "the ray cast reads the G-buffer";
        in.tubesInView = false;
        plan = planFrame(in);
        ASSERT_EQ(passes(plan), std::vector<Pass>{Pass::RayCast});
        EXPECT_EQ(std::find(plan.passes[0].reads.begin(), plan.passes[0].reads.end(), Resource::GBuffer), plan.passes[0].reads.end())
            << "without tubes in view the G-buffer is left out of its line";
    }
    PlanInputs in;
    in.shading = ShadingMode::Dos;
    in.tubes = in.tubesInView = true;
    EXPECT_EQ(passes(planFrame(in)), (std::vector<Pass>{Pass::TubeGBuffer, Pass::SlabPass, Pass::Composite}));
    in.tubesInView = false;
    EXPECT_EQ(passes(planFrame(in)), std::vector<Pass>{Pass::SlabPass});
}

TEST(FramePlan, DeclaredInputsTheSceneLacksAreLeftOut) {
    PlanInputs in;
    in.shading = ShadingMode::Phong;
    FramePlan plan = planFrame(in);
    ASSERT_EQ(plan.passes.size(), 1u);
    const std::vector<Resource>& reads = plan.passes[0].reads;
    EXPECT_EQ(std::count(reads.begin(), reads.end(), Resource::Ambient), 0) << "phong reads no V_AO";
    EXPECT_EQ(std::count(reads.begin(), reads.end(), Resource::ClipMaps), 0) << "no meshes, no maps";
    EXPECT_EQ(std::count(reads.begin(), reads.end(), Resource::Volume), 1);
    in.shading = ShadingMode::Lao;
    in.clipMeshes = 1;
    plan = planFrame(in);
    const std::vector<Resource>& caster = plan.passes.back().reads;
    EXPECT_EQ(std::count(caster.begin(), caster.end(), Resource::Ambient), 1);
    EXPECT_NE(plan.describe().find("V_AO (LAO under clipping)"), std::string::npos) << plan.describe();
}

TEST(FramePlan, TablesAreCompleteAndNamedOnce) {
    std::set<std::string> names;
    for (const PassInfo& p : allPasses()) {
        EXPECT_EQ(&passInfo(p.id), &p) << p.name;
        EXPECT_TRUE(names.insert(p.name).second) << "two passes named " << p.name;
        EXPECT_FALSE(p.writes.empty()) << p.name;
    }
    std::set<std::string> resources;
    for (int r = 0; r < static_cast<int>(Resource::Count); ++r)
        EXPECT_TRUE(resources.insert(resourceInfo(static_cast<Resource>(r)).name).second);
    // The timings name AO passes through the table, not by a prefix of their names.
    FrameTimings t{{{Pass::LaoPrecompute, 5.0}, {Pass::VoxelClipping, 1.0}, {Pass::LaoRecompute, 2.0}, {Pass::RayCast, 10.0}}};
    EXPECT_DOUBLE_EQ(t.ambientOcclusionMs(), 8.0);
    EXPECT_DOUBLE_EQ(t.ms(Pass::RayCast), 10.0);
}

TEST(ShadingModes, TheCycleVisitsEveryModeOnce) {
    std::set<ShadingMode> seen;
    ShadingMode m = ShadingMode::Solid;
    for (std::size_t i = 0; i < allShadingModes().size(); ++i, m = nextShadingMode(m)) EXPECT_TRUE(seen.insert(m).second);
    EXPECT_EQ(m, ShadingMode::Solid);
    EXPECT_EQ(seen.size(), allShadingModes().size());
}

TEST(ShaderInterface, DeclaredUniformsAreParsedFromTheSource) {
    std::set<std::string> names = gl::declaredUniforms(
        "#version 450\nlayout(binding = 0) uniform sampler3D volumeData; // uniform float notThis;\n"
        "uniform vec3 lightDirection[4];\nuniform float a, b;\n/* uniform int hidden; */\n"
        "layout(std140, binding = 0) uniform Block { mat4 member; };\nvoid main() { float uniformish = 1.0; }\n");
    EXPECT_EQ(names, (std::set<std::string>{"volumeData", "lightDirection", "a", "b"}));
}

TEST(ShaderInterface, SettingAnUndeclaredUniformIsAnError) {
    test::glContext();
    gl::Program p = gl::Program::compute("raycast.comp", {{"SHADING", "0"}, {"LIGHT_COUNT", "1"}});
    EXPECT_NO_THROW(p.set("stepMm", 0.5f));
    EXPECT_NO_THROW(p.set("ambientScale", 2.0f)) << "declared under #if (lao/cao), compiled out in solid: ignored";
    EXPECT_THROW(p.set("stepMM", 0.5f), SystemError) << "a typo must not pass silently";
    EXPECT_THROW(p.set("sliceDistance", 1.0f), SystemError) << "a slab-pass uniform on the ray caster";
}

}  // namespace
}  // namespace curette
