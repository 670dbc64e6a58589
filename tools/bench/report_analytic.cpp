#include "tools/bench/report_analytic.h"

#include "mesh/primitives.h"
#include "plan/removal_report.h"
#include "render/passes/removal_probe.h"
#include "render/renderer.h"
#include "render/model/lao_settings.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <chrono>
#include <cmath>
#include <memory>

namespace curette::bench {

namespace {

struct Grid {
    const char* name;
    glm::dvec3 spacing;
    glm::dquat tilt;   // the grid's axes turned in the world (an oblique acquisition)
};

// A grid of `spacing` holding a cube of side `extentMm` around the origin, turned by `tilt`.
glm::dmat4 gridAffine(const Grid& g, double extentMm, glm::ivec3& dims) {
    dims = glm::ivec3(glm::ceil(glm::dvec3(extentMm) / g.spacing)) + 1;
    glm::dmat4 scale(1.0);
    for (int a = 0; a < 3; ++a) scale[a][a] = g.spacing[a];
    return glm::mat4_cast(g.tilt) * scale * glm::translate(glm::dmat4(1.0), -0.5 * glm::dvec3(dims - 1));
}

VolumeData uniformScan(glm::ivec3 dims, const glm::dmat4& affine) {
    VolumeData v;
    v.dims = dims;
    v.indexToWorld = affine;
    v.format = StorageFormat::UNorm8;
    v.voxels.assign(v.voxelCount(), 200);
    v.valueScale = 255.0;
    v.minValue = v.maxValue = 200;
    v.source = "<uniform scan>";
    return v;
}

TransferFunction opaque() {
    TransferFunction tf;
    tf.name = "opaque";
    tf.color = {{0.0, glm::dvec3(1.0)}};
    tf.opacity = {{0.0, 1.0}, {255.0, 1.0}};
    return tf;
}

using Clock = std::chrono::steady_clock;

// The report of one posed mesh on `volume`, with `labels` (may be empty) as one protected label set; with
// `imageRemovedMl`, also the volume step IV's coverage at the renderer's N removes, from the same clip maps.
plan::Report reportOf(gl::Context& context, const VolumeData& volume, const clip::TriangleMesh& mesh, const clip::RigidPose& pose,
                      const std::vector<plan::LabelSet>& labels, double& ms, double* imageRemovedMl = nullptr) {
    const TransferFunction tf = opaque();
    Renderer renderer(context, volume, tf);
    renderer.clipMeshes().add(std::make_shared<const clip::TriangleMesh>(mesh), glm::dvec3(1.0), pose, "carve");
    plan::ReportSettings settings;
    settings.tissue = plan::TissueRule::All;
    auto reportAt = [&](int samples) {
        RemovalProbe probe(renderer.geometry(), samples);
        plan::RemovalField field = probe.removalField(renderer.clipMeshes());
        plan::PointsInside inside = [&](const std::vector<glm::dvec3>& p) { return probe.insideFlags(renderer.clipMeshes(), p); };
        return plan::computeReport(volume, tf, settings, field, labels, {}, inside);
    };
    const Clock::time_point start = Clock::now();
    plan::Report report = reportAt(plan::kReportAntiAliasingSamples);
    ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    if (imageRemovedMl) *imageRemovedMl = reportAt(LaoSettings{}.antiAliasingSamples).removedMl;
    return report;
}

// A volume case: the report's removal and its bound, and the image's removal beside it.
void measureVolume(gl::Context& context, const VolumeData& volume, const clip::TriangleMesh& mesh, const clip::RigidPose& pose,
                   AnalyticCase& c) {
    plan::Report r = reportOf(context, volume, mesh, pose, {}, c.ms, &c.atImageSamples);
    c.reported = r.removedMl, c.uncertainty = r.removedUncertaintyMl;
}

void volumeCases(gl::Context& context, std::vector<AnalyticCase>& out) {
    const std::vector<Grid> grids = {
        {"1 mm", glm::dvec3(1.0), glm::dquat(1, 0, 0, 0)},
        {"0.5x0.5x3 tilted", glm::dvec3(0.5, 0.5, 3.0), glm::angleAxis(glm::radians(17.0), glm::normalize(glm::dvec3(1, 0.3, 0)))}};
    const std::vector<std::pair<std::string, clip::TriangleMesh>> shapes = {
        {"box 5", clip::makeBox(glm::dvec3(5))},
        {"box 10", clip::makeBox(glm::dvec3(10))},
        {"box 30", clip::makeBox(glm::dvec3(30))},
        {"box 30x40x50", clip::makeBox(glm::dvec3(30, 40, 50))},
        {"box 60x80x100", clip::makeBox(glm::dvec3(60, 80, 100))},
        {"sphere r 20", clip::makeSphere(20.0, 6)},
        {"cylinder r 8 h 30", clip::makeCylinder(8.0, 30.0, 128)},
        {"capsule r 6 l 20", clip::makeCapsule(6.0, 20.0, 96)},
        {"torus 20 / 6", clip::makeTorus(20.0, 6.0, 192, 96)}};
    const std::vector<std::pair<std::string, glm::dquat>> turns = {
        {"", glm::dquat(1, 0, 0, 0)}, {", turned", glm::angleAxis(glm::radians(33.0), glm::normalize(glm::dvec3(1, 2, 3)))}};
    for (const Grid& g : grids)
        for (const auto& [name, mesh] : shapes)
            for (const auto& [turnName, turn] : turns) {
                const double extent = glm::length(mesh.boundsMax() - mesh.boundsMin()) + 12.0;
                glm::ivec3 dims;
                const glm::dmat4 affine = gridAffine(g, extent, dims);
                AnalyticCase c{"volume", g.name, name + turnName, std::abs(mesh.signedVolume()) / 1000.0};
                // Off the lattice, so no face lies on a cell face by construction.
                measureVolume(context, uniformScan(dims, affine), mesh, {glm::dvec3(0.37, -0.21, 0.13), turn}, c);
                out.push_back(c);
            }
    // A 20 x 14 x 16 mm box reaching 3.7 mm past the scan's +x face.
    const Grid g = grids.front();
    glm::ivec3 dims;
    const glm::dmat4 affine = gridAffine(g, 40.0, dims);
    const double face = 0.5 * (dims.x - 1) + 0.5;
    const glm::dvec3 size(20.0, 14.0, 16.0);
    AnalyticCase c{"volume", g.name, "box partly outside", (size.x - 3.7) * size.y * size.z / 1000.0};
    measureVolume(context, uniformScan(dims, affine), clip::makeBox(size), {glm::dvec3(face + 3.7 - 0.5 * size.x, 0.37, -0.21), {}}, c);
    out.push_back(c);
}

void marginCases(gl::Context& context, std::vector<AnalyticCase>& out) {
    const glm::ivec3 dims(48, 24, 24);
    const VolumeData volume = uniformScan(dims, glm::dmat4(1.0));
    LabelMap wall;
    wall.dims = dims;
    wall.indexToWorld = glm::dmat4(1.0);
    wall.source = "<wall>";
    wall.ids.resize(wall.voxelCount());
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i) wall.ids[wall.linearIndex(i, j, k)] = i >= 32 ? 1 : 0;
    LabelTable table;
    table.entries = {{1, "Wall", glm::dvec4(1.0)}};
    const std::vector<plan::LabelSet> labels = {{"walls", &wall, &table, {1}, {}}};
    struct Case {
        std::string name;
        clip::TriangleMesh mesh;
        clip::RigidPose pose;
        double gap;
    };
    // Boxes 22 x 12 x 12 mm whose +x face lies at 31.5 - gap; a turned box; a sphere.
    auto boxEndingAt = [](double x) { return clip::RigidPose{glm::dvec3(x - 11.0, 11.5, 11.5), {}}; };
    const glm::dvec3 half(5.0, 3.0, 4.0);
    const double r = 7.0, turn = glm::radians(30.0);
    std::vector<Case> cases = {
        {"box touching", clip::makeBox({22, 12, 12}), boxEndingAt(31.5), 0.0},
        {"box 1 mm away", clip::makeBox({22, 12, 12}), boxEndingAt(30.5), 1.0},
        {"box 2 mm away", clip::makeBox({22, 12, 12}), boxEndingAt(29.5), 2.0},
        {"box 4 mm away", clip::makeBox({22, 12, 12}), boxEndingAt(27.5), 4.0},
        {"box 0.6 mm away", clip::makeBox({22, 12, 12}), boxEndingAt(30.9), 0.6},
        {"box 2.2 mm away", clip::makeBox({22, 12, 12}), boxEndingAt(29.3), 2.2},
        {"box turned 30 deg", clip::makeBox(2.0 * half), {glm::dvec3(18.0, 12.0, 12.0), glm::angleAxis(turn, glm::dvec3(0, 0, 1))},
         31.5 - (18.0 + half.x * std::cos(turn) + half.y * std::sin(turn))},
        {"sphere 1.37 mm away", clip::makeSphere(r, 6), {glm::dvec3(31.5 - r - 1.37, 11.8, 12.3), {}}, 1.37}};
    for (const Case& m : cases) {
        AnalyticCase c{"margin", "1 mm", m.name, m.gap};
        plan::Report report = reportOf(context, volume, m.mesh, m.pose, labels, c.ms);
        const plan::StructureRow& row = report.structures.front();
        c.reported = row.marginMm, c.uncertainty = row.marginUncertaintyMm, c.wallTouched = row.touched;
        out.push_back(c);
    }
}

}  // namespace

std::vector<AnalyticCase> analyticReportCases(gl::Context& context) {
    std::vector<AnalyticCase> out;
    volumeCases(context, out);
    marginCases(context, out);
    return out;
}

}  // namespace curette::bench
