// The frame plan's declarations are checked, not only printed: every resource a pass's programs really bind
// (the GL's introspection of the programs the pass made current, render/pass_bindings.h) is one the pass declares
// as read or written (render/model/frame_plan.cpp), in every mode, with labels, clip meshes and tubes, whole and
// in slices, and in previews. A shader that starts reading a resource its pass does not declare fails here.
#include "tests/render/moving_sphere_scene.h"

#include "render/label_overlay.h"
#include "render/model/tube_impostors.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace curette {
namespace {

using test::MovingSphereScene;

std::string resourceNames(const std::set<Resource>& resources) {
    std::string text;
    for (Resource r : resources) text += std::string(text.empty() ? "" : ", ") + resourceInfo(r).name;
    return text;
}

// Every pass of the image shown bound only what the pass declares (render/model/frame_plan.cpp).
void expectBoundIsDeclared(const Renderer& renderer, const char* what) {
    const FramePlan& plan = renderer.lastPlan();
    const std::vector<BoundResources>& bound = renderer.lastPassBindings();
    ASSERT_EQ(bound.size(), plan.passes.size()) << what << ": every pass is audited";
    for (std::size_t i = 0; i < plan.passes.size(); ++i) {
        const PlannedPass& planned = plan.passes[i];
        ASSERT_EQ(bound[i].pass, planned.pass);
        std::set<Resource> undeclared;
        const PassInfo& info = passInfo(planned.pass);
        for (Resource r : bound[i].resources) {
            bool declared = std::find(info.reads.begin(), info.reads.end(), r) != info.reads.end() ||
                            std::find(info.writes.begin(), info.writes.end(), r) != info.writes.end();
            if (!declared) undeclared.insert(r);
        }
        EXPECT_TRUE(undeclared.empty()) << what << ": pass \"" << passInfo(planned.pass).name << "\" binds " << resourceNames(undeclared)
                                        << " without declaring it";
        std::string unknown;
        for (const std::string& u : bound[i].unknown) unknown += u + " ";
        EXPECT_TRUE(bound[i].unknown.empty()) << what << ": pass \"" << passInfo(planned.pass).name << "\" binds units no resource stands for: " << unknown;
        EXPECT_FALSE(bound[i].resources.empty()) << what << ": pass \"" << passInfo(planned.pass).name << "\" bound nothing: the audit saw no program";
    }
}

void addLabels(MovingSphereScene& s) {
    glm::ivec3 dims = s.volume.dims;
    std::vector<std::uint16_t> ids(static_cast<std::size_t>(dims.x) * dims.y * dims.z, 0);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = dims.x / 2; x < dims.x; ++x) ids[static_cast<std::size_t>(x + dims.x * (y + dims.y * z))] = 1;
    s.renderer->setLabels(std::make_unique<LabelOverlay>(dims, ids, std::vector<glm::vec4>{glm::vec4(0), glm::vec4(0.9f, 0.2f, 0.2f, 0.3f)}));
}

struct Case {
    ShadingMode mode;
    bool tubes;
    bool ismosFit = false;
    bool impostors = false;   // the tubes as impostors (the compute G-buffer)
};

// One straight impostor segment where test::straightTube lies.
TubeImpostors straightImpostor() {
    TubeImpostors t;
    t.points = {{glm::vec3(0, -2, -7), packImpostorColor(glm::vec4(1), kImpostorSegmentStarts)},
                {glm::vec3(0, -2, 7), packImpostorColor(glm::vec4(1), kImpostorSegmentEnds)}};
    t.bundles = {TubeImpostorBundle{0, 2, 2.0, false}};
    t.streamlines = 1;
    t.boundsMin = glm::dvec3(-2, -4, -9), t.boundsMax = glm::dvec3(2, 0, 9);
    return t;
}

TEST(PassDeclarations, EveryBoundResourceIsDeclared) {
    const Case cases[] = {{ShadingMode::Solid, false}, {ShadingMode::Phong, false}, {ShadingMode::Lao, false},
                          {ShadingMode::Cao, false},   {ShadingMode::Dos, false},   {ShadingMode::Ismos, false},
                          {ShadingMode::Ismos, false, true}, {ShadingMode::Cao, true}, {ShadingMode::Dos, true},
                          {ShadingMode::Phong, true},  {ShadingMode::Ismos, true}, {ShadingMode::Phong, true, false, true},
                          {ShadingMode::Dos, true, false, true}};
    for (const Case& c : cases) {
        std::string what = std::string(shadingModeName(c.mode)) + (c.tubes ? c.impostors ? " with impostor tubes" : " with tubes" : "") +
                           (c.ismosFit ? " (fit)" : "");
        SCOPED_TRACE(what);
        MovingSphereScene s(c.mode);
        addLabels(s);
        if (c.impostors) s.renderer->setTubeImpostors(straightImpostor(), TubeShading{});
        else if (c.tubes) s.renderer->setTubes(test::straightTube(glm::dvec3(0, -2, 0), glm::dvec3(0, 0, 1), 14.0, 2.0, glm::vec4(1)), TubeShading{});
        s.frame.ismos.partial = true;
        s.frame.ismos.fit = c.ismosFit;
        s.renderer->setAuditBindings(true);
        s.renderer->render(s.frame);   // every pass of the mode: maps, step I, IV, V, the image passes
        expectBoundIsDeclared(*s.renderer, (what + ", exact").c_str());
        s.moveTo(2);
        FrameDescription small = s.frame;
        small.size = {24, 20};
        s.renderer->renderPreview(small);
        expectBoundIsDeclared(*s.renderer, (what + ", preview").c_str());
        while (!s.renderer->advanceExact(s.frame, 0.0, 3)) {}
        expectBoundIsDeclared(*s.renderer, (what + ", in slices").c_str());
    }
}

// The audit sees what a pass binds: without labels no pass binds the label volume; with them the passes that
// classify samples do (so a declaration left out is caught, which it was for the label volume).
TEST(PassDeclarations, TheAuditSeesTheLabelVolume) {
    auto bindsLabels = [](bool labels) {
        MovingSphereScene s(ShadingMode::Cao);
        if (labels) addLabels(s);
        s.renderer->setAuditBindings(true);
        s.renderer->render(s.frame);
        std::set<Pass> passes;
        for (const BoundResources& b : s.renderer->lastPassBindings())
            if (b.resources.count(Resource::LabelVolume)) passes.insert(b.pass);
        return passes;
    };
    EXPECT_TRUE(bindsLabels(false).empty());
    std::set<Pass> with = bindsLabels(true);
    EXPECT_TRUE(with.count(Pass::LaoPrecompute));
    EXPECT_TRUE(with.count(Pass::VoxelClipping));
    EXPECT_TRUE(with.count(Pass::RayCast));
}

}  // namespace
}  // namespace curette
