#include "scene/scene_keys.h"

#include "io/transfer_function_file.h"
#include "base/error.h"
#include "mesh/mesh_description.h"
#include "render/model/setting_limits.h"

#include <glm/gtc/quaternion.hpp>

namespace curette {

namespace {
// A value within one of the limits the passes also check (render/model/setting_limits.h).
int within(const JsonReader& r, const IntLimit& limit) { return r.integer(limit.min, limit.max); }
double within(const JsonReader& r, const NumberLimit& limit) {
    if (!r.isNumber()) r.fail(limit.expected());
    double v = r.number();
    if (!limit.contains(v)) r.fail(limit.expected());
    return v;
}
}  // namespace

ShadingMode readShading(const JsonReader& r) {
    auto mode = parseShadingMode(r.isString() ? r.string() : "");
    if (!mode) r.fail("one of " + shadingModeList());
    return *mode;
}

TransferFunction readInlineTransferFunction(const JsonReader& r) {
    return io::parseTransferFunctionJson(r.json(), r.file(), r.path());
}

Light readLight(const JsonReader& r, IsmosLightShape& shape) {
    Light light;
    light.direction = r.at("direction").vec3();
    if (glm::length(light.direction) < 1e-9) r.at("direction").fail("a non-zero direction");
    glm::dvec3 color(1.0);
    if (auto c = r.find("color")) color = c->vec3(0, 1);
    double intensity = 1.0;
    if (auto i = r.find("intensity")) intensity = i->number(0, 100);
    light.color = color * intensity;
    if (auto s = r.find("space")) light.cameraSpace = s->oneOf({"camera", "world"}) == "camera";
    if (auto d = r.find("disk_radius")) shape.diskRadius = d->number(0, 10);
    if (auto spot = r.find("spot")) {
        shape.spotAngleDeg = spot->at("angle_deg").number(0.1, 180);
        if (auto t = spot->find("target")) shape.spotTarget = t->vec3();
        spot->finish();
    }
    r.finish();
    return light;
}

LaoSettings readLao(const JsonReader& r) {
    LaoSettings lao;
    if (auto rays = r.find("rays")) {
        std::string text = rays->isNumber() ? std::to_string(rays->integer(1, 4096)) : rays->string();
        if (!parseLaoPattern(text, lao.directions))
            rays->fail("one of \"6\", \"14\", \"26\", \"54\" (the paper's patterns) or \"fibonacci:K\" with K in [1, 4096]");
    }
    if (auto m = r.find("samples")) lao.samples = within(*m, limits::laoSamples);
    if (auto s = r.find("step_mm")) lao.stepMm = within(*s, limits::laoStepMm);
    if (auto n = r.find("antialiasing_samples")) lao.antiAliasingSamples = within(*n, limits::laoAntiAliasingSamples);
    if (auto j = r.find("jitter")) lao.directions.jitter = j->number(0, 0.5);
    if (auto w = r.find("weights")) lao.directions.skyWeighting = w->oneOf({"uniform", "sky"}) == "sky";
    if (auto a = r.find("ambient_scale")) lao.ambientScale = a->number(0, 10);
    if (auto d = r.find("dispatch"))
        lao.dispatch = d->oneOf({"compacted", "full_grid"}) == "full_grid" ? LaoSettings::Dispatch::FullGrid
                                                                             : LaoSettings::Dispatch::Compacted;
    r.finish();
    return lao;
}

RaycastSettings readRaycast(const JsonReader& r) {
    RaycastSettings rc;
    if (auto s = r.find("step_mm")) rc.stepMm = s->number(0, 100);
    if (auto e = r.find("early_termination")) rc.earlyTerminationAlpha = e->number(0.5, 1.0);
    if (auto j = r.find("jitter_seed")) rc.jitterSeed = static_cast<std::uint32_t>(j->unsignedInteger(UINT32_MAX));
    if (auto k = r.find("skip_empty_space")) rc.skipEmptySpace = k->boolean();
    if (auto faces = r.find("cut_faces")) {
        CutFaceSettings& f = rc.cutFace;
        if (auto e = faces->find("enabled")) f.enabled = e->boolean();
        if (auto d = faces->find("normal_depth_mm")) f.normalDepthMm = d->number(0.01, 100);
        if (auto o = faces->find("normal_opacity")) f.normalOpacity = o->number(0.01, 1.0);
        faces->finish();
    }
    r.finish();
    return rc;
}

DosSettings readDos(const JsonReader& r) {
    DosSettings d;
    if (auto v = r.find("cone_angle_deg")) d.coneAngleDeg = within(*v, limits::dosConeAngleDeg);
    if (auto v = r.find("grid")) d.gridSize = within(*v, limits::dosGrid);
    if (auto v = r.find("slice_distance_mm")) d.sliceDistanceMm = within(*v, limits::dosSliceDistanceMm);
    if (auto v = r.find("ambient")) d.ambientRadiance = within(*v, limits::dosAmbient);
    r.finish();
    return d;
}

IsmosSettings readIsmos(const JsonReader& r) {
    IsmosSettings s;
    if (auto v = r.find("occlusion")) s.partial = v->oneOf({"partial", "full"}) == "partial";
    if (auto v = r.find("opacity")) s.fit = v->oneOf({"exact", "fit"}) == "fit";
    if (auto v = r.find("layers")) s.layers = v->integer(1, 4);
    if (auto v = r.find("blend_layers")) s.blendLayers = v->boolean();
    if (auto v = r.find("light_samples")) s.lightSamples = v->integer(1, 1024);
    if (auto v = r.find("test_points")) s.testPoints = v->integer(1, 4096);
    if (auto v = r.find("hemisphere_radius")) s.hemisphereRadius = v->number(0.01, 100);
    if (auto v = r.find("disk_radius")) s.diskRadius = v->number(0, 10);
    if (auto v = r.find("ambient")) s.ambient = v->number(0, 1);
    if (auto v = r.find("opacity_threshold")) s.opacityThreshold = v->number(0, 1);
    if (auto v = r.find("depth_bias")) s.depthBias = v->number(0, 1);
    if (auto v = r.find("falloff")) s.falloff = v->boolean();
    if (auto v = r.find("light_positions")) s.sphere = v->oneOf({"hemisphere", "sphere"}) == "sphere";
    if (auto v = r.find("base")) s.base = v->oneOf({"phong", "solid"}) == "solid" ? ShadingMode::Solid : ShadingMode::Phong;
    r.finish();
    return s;
}

TubeRendering readTubeRendering(const JsonReader& r) {
    TubeRendering out;
    TubeShading& t = out.shading;
    if (auto v = r.find("mode")) out.lines = v->oneOf({"tubes", "lines"}) == "lines";
    if (auto v = r.find("build")) {
        std::string build = v->oneOf({"cpu", "gpu", "impostor"});
        out.build = build == "gpu" ? TubeBuild::Gpu : build == "impostor" ? TubeBuild::Impostor : TubeBuild::Cpu;
    }
    if (auto v = r.find("geometry_opacity")) t.geometryOpacity = v->number(0, 1);
    if (auto v = r.find("vicinity_distance_mm")) t.vicinityDistanceMm = v->number(0, 1000);
    if (auto v = r.find("vicinity_samples")) t.vicinitySamples = v->integer(1, 256);
    if (auto v = r.find("depth_bias_mm")) t.depthBiasMm = v->number(0, 100);
    if (auto v = r.find("line_diffuse_exponent")) t.lineDiffuseExponent = v->number(0.1, 20);
    if (auto m = r.find("material")) io::readMaterial(*m, t.material);
    r.finish();
    return out;
}

void readTubeKeys(const JsonReader& r, SceneTubes& t, const std::string& where) {
    TubeSettings& s = t.settings;
    if (auto v = r.find("radius_mm")) s.radiusMm = v->number(1e-3, 100);
    if (auto v = r.find("sides")) s.sides = v->integer(3, 64);
    if (auto v = r.find("caps")) s.caps = v->boolean();
    if (auto v = r.find("smoothing")) s.smoothing = v->oneOf({"catmull-rom", "none"}) == "none" ? TubeSettings::Smoothing::None
                                                                                                 : TubeSettings::Smoothing::CatmullRom;
    if (auto v = r.find("step_mm")) s.stepMm = v->number(1e-2, 100);
    if (auto c = r.find("color")) {
        if (c->isArray()) {
            s.coloring = TubeSettings::Coloring::Uniform;
            s.uniformColor = c->vec3(0, 1);
        } else {
            s.coloring = c->oneOf({"direction", "scalar"}) == "scalar" ? TubeSettings::Coloring::Scalar : TubeSettings::Coloring::Direction;
        }
    }
    if (auto v = r.find("scalar")) s.scalarName = v->string();
    if (auto v = r.find("scalar_range")) {
        glm::dvec2 range = v->vec2();
        s.scalarMin = range.x, s.scalarMax = range.y;
    }
    if (s.coloring == TubeSettings::Coloring::Scalar && s.scalarName.empty())
        throw InputError(where, r.path() + ".scalar", "the name of a per-point scalar for \"color\": \"scalar\"", "nothing");
    if (auto v = r.find("name")) t.name = v->string();
    if (auto v = r.find("protected")) t.protectedBundle = v->boolean();
    r.finish();
}

std::shared_ptr<const clip::TriangleMesh> readMeshGeometry(const JsonReader& r, const std::filesystem::path& directory) {
    return std::make_shared<const clip::TriangleMesh>(clip::meshFromJson(r, directory));
}

ClipMeshDisplaySpec readClipMeshDisplay(const JsonReader& r) {
    ClipMeshDisplaySpec spec;
    if (auto v = r.find("show")) spec.show = v->boolean();
    if (auto v = r.find("opacity")) spec.display.fillOpacity = v->number(0, 1);
    if (auto v = r.find("outline_opacity")) spec.display.outlineOpacity = v->number(0, 1);
    r.finish();
    return spec;
}

glm::dvec3 readMeshScale(const JsonReader& r) { return r.isNumber() ? glm::dvec3(r.number(1e-6, 1e6)) : r.vec3(1e-6, 1e6); }

void readMeshPoseKeys(const JsonReader& r, clip::RigidPose& pose) {
    if (auto p = r.find("position_mm")) pose.position = p->vec3(-1e5, 1e5);
    if (auto rot = r.find("rotation_deg")) pose.orientation = clip::orientationFromDegrees(rot->vec3(-3600, 3600));
}

clip::RigidPose readMeshPose(const JsonReader& r) {
    clip::RigidPose pose;
    readMeshPoseKeys(r, pose);
    r.finish();
    return pose;
}

SceneClipMesh readClipMesh(const JsonReader& r, const std::filesystem::path& directory, std::size_t index) {
    SceneClipMesh mesh;
    mesh.name = "mesh " + std::to_string(index);
    if (auto n = r.find("name")) mesh.name = n->string();
    mesh.geometry = readMeshGeometry(r.at("mesh"), directory);
    readMeshPoseKeys(r, mesh.pose);
    if (auto c = r.find("clips_tubes")) mesh.clipsTubes = c->boolean();
    if (auto s = r.find("scale")) mesh.scale = readMeshScale(*s);
    r.finish();
    return mesh;
}

}  // namespace curette
