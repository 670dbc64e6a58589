#include "render/model/frame_plan.h"

#include <algorithm>

namespace curette {

namespace {
using R = Resource;
// What each pass may read and write: every resource its programs bind, which the test
// PassDeclarations.EveryBoundResourceIsDeclared holds against the GL's introspection of the programs it ran.
const PassInfo kPasses[] = {
    {Pass::ClipMaps, "II-III clip maps", "CAO steps II-III: depth peeling, 2-D Minkowski dilation", {R::ClipMeshGeometry}, {R::ClipMaps}, false, "where the tools cut"},
    // Phase 1 is step IV's kernel without meshes (V_o, V_m); phase 2 the LAO of every voxel.
    {Pass::LaoPrecompute, "I LAO precompute", "CAO step I: LAO of every voxel, eq. 2-3",
     {R::Volume, R::TransferFunction, R::GradientOpacity, R::LabelVolume, R::DrilledRemoval, R::ClipMaps, R::LaoDirections, R::SeenBricks, R::VisitedBricks},
     {R::ClippedOpacity, R::CategoryMask, R::PrecomputedAo, R::RecomputeList}, true, "occlusion of the scan"},
    {Pass::VoxelClipping, "IV voxel clipping", "CAO step IV: anti-aliased shadow-test clipping, Algorithm 2",
     {R::Volume, R::TransferFunction, R::GradientOpacity, R::LabelVolume, R::DrilledRemoval, R::ClipMaps, R::VisitedBricks},
     {R::ClippedOpacity, R::CategoryMask, R::VisitedBricks}, true, "the carve"},
    {Pass::LaoRecompute, "V LAO recompute", "CAO step V: LAO of category-b voxels",
     {R::ClippedOpacity, R::CategoryMask, R::PrecomputedAo, R::LaoDirections, R::SeenBricks, R::VisitedBricks}, {R::RecomputeList, R::Ambient}, true, "occlusion under the carve"},
    {Pass::TubeGBuffer, "tubes G-buffer", "DOS+geometry section 3.1.1", {R::TubeGeometry, R::ClipMaps}, {R::GBuffer}, false, "fiber tubes"},
    // With tubes in view the ray stops at the G-buffer's surface and shades it (shaders/tube_surface.glsl).
    {Pass::RayCast, "VI ray casting", "CAO step VI: ray casting with shadow-test clipping",
     {R::Volume, R::GradientVolume, R::TransferFunction, R::GradientOpacity, R::LabelVolume, R::DrilledRemoval, R::Occupancy, R::ClipMaps, R::Ambient, R::GBuffer},
     {R::OutputImage}, false, "full-quality image"},
    {Pass::SlabPass, "slab pass", "DOS Algorithms 1, 3; DOS+geometry Algorithms 2-4",
     {R::Volume, R::TransferFunction, R::GradientOpacity, R::LabelVolume, R::DrilledRemoval, R::ClipMaps, R::Ambient, R::GBuffer},
     {R::OcclusionBuffers, R::GBuffer, R::OutputImage}, false, "shadows (directional occlusion)"},
    {Pass::Composite, "composite + vicinity", "DOS+geometry Algorithms 5-6", {R::GBuffer, R::OutputImage}, {R::OutputImage}, false, "shading the tubes"},
    {Pass::IsmosRayCast, "ISMOS 1 ray casting + layers", "ISMOS sec. 3.5-3.6: colour, 4 depth layers, transmittance fit",
     {R::Volume, R::TransferFunction, R::GradientOpacity, R::LabelVolume, R::DrilledRemoval, R::Occupancy, R::ClipMaps, R::GBuffer},
     {R::OutputImage, R::IsmosLayers, R::IsmosLayerBacks, R::IsmosFit}, false, "full-quality image and its depth layers"},
    {Pass::IsmosOcclusion, "ISMOS 2 occlusion", "ISMOS sec. 3.3-3.7: full/partial occlusion, eq. 1-5, 13-16",
     {R::IsmosLayers, R::IsmosLayerBacks, R::IsmosFit, R::IsmosLightSamples, R::OutputImage}, {R::OutputImage}, true, "shadows (multidirectional occlusion)"},
    {Pass::GradientVolume, "gradient volume", "phong's central differences per voxel (render/gradient_volume.h)", {R::Volume},
     {R::GradientVolume}, false, "gradients of the scan"},
};
static_assert(std::size(kPasses) == static_cast<std::size_t>(Pass::Count));
}  // namespace

const PassInfo& passInfo(Pass pass) { return kPasses[static_cast<std::size_t>(pass)]; }
std::span<const PassInfo> allPasses() { return kPasses; }

bool Freshness::samePrecomputeInputs(const InputVersions& a, const InputVersions& b) {
    return a.volume == b.volume && a.transferFunction == b.transferFunction && a.laoSettings == b.laoSettings;
}

bool Freshness::precomputedCurrent(const InputVersions& now) const { return precomputed_ && samePrecomputeInputs(*precomputed_, now); }

bool Freshness::ambientCurrent(const InputVersions& now, ShadingMode mode) const {
    return precomputedCurrent(now) && ambient_ && *ambient_ == now && ambientMode_ == mode;
}

FramePlan planFrame(const PlanInputs& in) {
    const ShadingModeTraits& mode = traits(in.shading);
    bool tubes = in.tubes && in.tubesInView;
    // Phong's ray cast reads its gradients from the gradient volume where the scan has one (the slab pass and
    // ISMOS keep the six reads).
    bool gradients = in.gradientVolume && in.shading == ShadingMode::Phong;
    // Resources this frame has at all: a pass's declared input that the scene lacks is left out of its line.
    auto present = [&](Resource r) {
        switch (r) {
            case R::ClipMeshGeometry:
            case R::ClipMaps: return in.clipMeshes > 0;
            case R::ClippedOpacity:
            case R::CategoryMask:
            case R::PrecomputedAo:
            case R::Ambient:
            case R::RecomputeList:
            case R::VisitedBricks:
            case R::SeenBricks:
            case R::LaoDirections: return mode.ambientOcclusion;
            case R::LabelVolume: return in.labels;
            case R::GradientVolume: return gradients;
            case R::DrilledRemoval: return in.drilled;
            case R::TubeGeometry:
            case R::GBuffer: return tubes;
            case R::IsmosLayers:
            case R::IsmosLightSamples: return in.shading == ShadingMode::Ismos;
            case R::IsmosLayerBacks: return in.shading == ShadingMode::Ismos && in.ismosExact;
            case R::IsmosFit: return in.shading == ShadingMode::Ismos && in.ismosFit;
            default: return true;
        }
    };
    FramePlan plan;
    auto add = [&](Pass p) {
        PlannedPass planned{p, {}, {}};
        for (Resource r : passInfo(p).reads)
            if (present(r)) planned.reads.push_back(r);
        for (Resource r : passInfo(p).writes)
            if (present(r)) planned.writes.push_back(r);
        plan.passes.push_back(std::move(planned));
    };
    if (gradients && !in.gradientVolumeCurrent) add(Pass::GradientVolume);
    if (in.clipMeshes > 0 && !in.clipMapsCurrent) add(Pass::ClipMaps);
    if (mode.ambientOcclusion) {
        if (!in.precomputedCurrent) add(Pass::LaoPrecompute);
        if (!in.precomputedCurrent || !in.ambientCurrent) {
            add(Pass::VoxelClipping);
            add(Pass::LaoRecompute);
        }
    }
    if (tubes && in.shading == ShadingMode::Ismos) {
        // Seed 003 with tubes: the ray cast stops at the tube surface, which becomes an opaque layer; the
        // compositor lays the lit tube behind the volume, then the occlusion pass shades both.
        add(Pass::TubeGBuffer);
        add(Pass::IsmosRayCast);
        add(Pass::Composite);
        add(Pass::IsmosOcclusion);
    } else if (tubes && mode.tubesInSlabPass) {
        // dos: seed 000 Algorithm 1, G-buffer, slab pass, composite (the combined occlusion is the model).
        add(Pass::TubeGBuffer);
        add(Pass::SlabPass);
        add(Pass::Composite);
    } else if (tubes) {
        // solid, phong, lao, cao: no occlusion to propagate slice by slice, so the ray cast ends each ray at the
        // G-buffer's tube surface and shades it in the mode's light (lao/cao: V_AO at the surface).
        add(Pass::TubeGBuffer);
        add(Pass::RayCast);
    } else if (mode.slabPass) {
        add(Pass::SlabPass);
    } else if (in.shading == ShadingMode::Ismos) {
        // Seed 003: nothing precomputed, so a TF change or a moved light costs these two passes and no more.
        add(Pass::IsmosRayCast);
        add(Pass::IsmosOcclusion);
    } else {
        add(Pass::RayCast);
    }
    return plan;
}

bool FramePlan::runs(Pass pass) const {
    return std::any_of(passes.begin(), passes.end(), [&](const PlannedPass& p) { return p.pass == pass; });
}

bool FramePlan::reads(Pass pass, Resource resource) const {
    return std::any_of(passes.begin(), passes.end(), [&](const PlannedPass& p) {
        return p.pass == pass && std::find(p.reads.begin(), p.reads.end(), resource) != p.reads.end();
    });
}

std::string FramePlan::describe() const {
    auto list = [](const std::vector<Resource>& resources) {
        std::string text;
        for (Resource r : resources) text += (text.empty() ? "" : ", ") + std::string(resourceInfo(r).name);
        return text.empty() ? std::string("-") : text;
    };
    std::string out;
    int n = 0;
    for (const PlannedPass& p : passes) {
        const PassInfo& info = passInfo(p.pass);
        out += std::to_string(++n) + ". " + info.name + "  (" + info.implements + ")\n";
        out += "     reads:  " + list(p.reads) + "\n";
        out += "     writes: " + list(p.writes) + "\n";
    }
    return out;
}

double FrameTimings::ms(Pass pass) const {
    double sum = 0;
    for (const Entry& e : passes)
        if (e.pass == pass) sum += e.ms;
    return sum;
}

double FrameTimings::ambientOcclusionMs() const {
    double sum = 0;
    for (const Entry& e : passes)
        if (passInfo(e.pass).ambientOcclusion) sum += e.ms;
    return sum;
}

double FrameTimings::totalMs() const {
    double sum = 0;
    for (const Entry& e : passes) sum += e.ms;
    return sum;
}

}  // namespace curette
