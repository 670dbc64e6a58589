#include "app/scene.h"

#include "app/io/transfer_function_file.h"
#include "clip/mesh_description.h"
#include "clip/limits.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "base/json_reader.h"

#include <cstring>

namespace curette {

namespace fs = std::filesystem;

std::vector<std::string> fileNameStems(const fs::path& path) {
    std::vector<std::string> stems{path.filename().string()};
    for (bool stripped = true; stripped;) {
        stripped = false;
        for (const char* suffix : {".gz", ".nii", ".nrrd", ".mha", ".mhd", ".trk", ".tck", ".trx"}) {
            const std::string& name = stems.back();
            if (name.size() > std::strlen(suffix) && name.ends_with(suffix)) {
                stems.push_back(name.substr(0, name.size() - std::strlen(suffix)));
                stripped = true;
                break;
            }
        }
    }
    return stems;
}

namespace {

ScalarType parseScalarType(const JsonReader& r) {
    std::string name = r.oneOf({"uint8", "int16", "uint16", "int32", "float32", "float64"});
    if (name == "uint8") return ScalarType::UInt8;
    if (name == "int16") return ScalarType::Int16;
    if (name == "uint16") return ScalarType::UInt16;
    if (name == "int32") return ScalarType::Int32;
    if (name == "float32") return ScalarType::Float32;
    return ScalarType::Float64;
}

// "AF_L.trk" -> "AF_L", "aal.nii.gz" -> "aal": what a file is called in a report.
std::string fileStem(const fs::path& path) { return fileNameStems(path).back(); }

fs::path resolvePath(const fs::path& scene, const std::string& path) {
    fs::path p(path);
    return p.is_absolute() ? p : scene.parent_path() / p;
}

void parseVolume(const JsonReader& r, Scene& scene) {
    scene.volumePath = resolvePath(scene.file, r.at("path").string());
    if (auto format = r.find("format")) {
        std::string f = format->oneOf({"auto", "nifti", "nrrd", "raw", "metaimage", "dicom"});
        scene.volumeOptions.format = f == "nifti"       ? io::VolumeFormat::Nifti
                                     : f == "nrrd"      ? io::VolumeFormat::Nrrd
                                     : f == "raw"       ? io::VolumeFormat::Raw
                                     : f == "metaimage" ? io::VolumeFormat::MetaImage
                                     : f == "dicom"     ? io::VolumeFormat::Dicom
                                                        : io::VolumeFormat::Auto;
    }
    if (auto raw = r.find("raw")) {
        io::RawLayout layout;
        glm::dvec3 dims = raw->at("dims").vec3(1, 1e9);
        for (int a = 0; a < 3; ++a)
            if (dims[a] != std::floor(dims[a])) raw->at("dims").fail("three positive integers");
        layout.dims = glm::ivec3(dims);
        layout.type = parseScalarType(raw->at("type"));
        if (auto e = raw->find("endian")) layout.bigEndian = e->oneOf({"little", "big"}) == "big";
        if (auto s = raw->find("spacing")) layout.spacing = s->vec3(1e-9, 1e9);
        if (auto o = raw->find("origin")) layout.origin = o->vec3();
        if (auto h = raw->find("header_bytes")) layout.headerBytes = h->unsignedInteger();
        if (auto g = raw->find("gzip")) layout.gzip = g->boolean();
        raw->finish();
        scene.volumeOptions.raw = layout;
        if (scene.volumeOptions.format == io::VolumeFormat::Auto) scene.volumeOptions.format = io::VolumeFormat::Raw;
    }
    if (auto index = r.find("index")) scene.volumeOptions.volumeIndex = index->integer(0, 1 << 20);
    if (auto series = r.find("series"))
        scene.volumeOptions.series = series->isString() ? series->string() : std::to_string(series->integer(0, INT32_MAX));
    if (scene.volumeOptions.format == io::VolumeFormat::Raw && !scene.volumeOptions.raw)
        throw InputError(scene.file.string(), "volume.raw", "the raw layout (dims, type, ...) for format \"raw\"", "nothing");
    r.finish();
}

void parseCamera(const JsonReader& r, CameraSpec& camera) {
    if (auto t = r.find("target")) {
        if (t->isString()) {
            if (t->string() != "center") t->fail("\"center\" or [x, y, z] in mm");
        } else {
            camera.target = t->vec3();
        }
    }
    if (auto d = r.find("distance_mm")) {
        if (d->isString()) {
            if (d->string() != "fit") d->fail("\"fit\" or a distance in mm > 0");
        } else {
            camera.distanceMm = d->number(1e-3, 1e6);
        }
    }
    if (auto a = r.find("azimuth_deg")) camera.azimuthDeg = a->number(-360, 360);
    if (auto e = r.find("elevation_deg")) camera.elevationDeg = e->number(-89.9, 89.9);
    if (auto f = r.find("fov_deg")) camera.fovYDeg = f->number(1, 170);
    r.finish();
}

Light parseLight(const JsonReader& r, IsmosLightShape& shape) {
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

LaoSettings parseLao(const JsonReader& r) {
    LaoSettings lao;
    if (auto rays = r.find("rays")) {
        std::string text = rays->isNumber() ? std::to_string(rays->integer(1, 4096)) : rays->string();
        if (!parseLaoPattern(text, lao.directions))
            rays->fail("one of \"6\", \"14\", \"26\", \"54\" (the paper's patterns) or \"fibonacci:K\" with K in [1, 4096]");
    }
    if (auto m = r.find("samples")) lao.samples = m->integer(1, 1024);
    if (auto s = r.find("step_mm")) lao.stepMm = s->number(1e-3, 100);
    if (auto n = r.find("antialiasing_samples")) lao.antiAliasingSamples = n->integer(0, 256);
    if (auto j = r.find("jitter")) lao.directions.jitter = j->number(0, 0.5);
    if (auto w = r.find("weights")) lao.directions.skyWeighting = w->oneOf({"uniform", "sky"}) == "sky";
    if (auto a = r.find("ambient_scale")) lao.ambientScale = a->number(0, 10);
    if (auto d = r.find("dispatch"))
        lao.dispatch = d->oneOf({"compacted", "full_grid"}) == "full_grid" ? LaoSettings::Dispatch::FullGrid
                                                                             : LaoSettings::Dispatch::Compacted;
    r.finish();
    return lao;
}

SceneClipMesh parseClipMesh(const JsonReader& r, const fs::path& sceneFile, std::size_t index) {
    SceneClipMesh mesh;
    mesh.name = "mesh " + std::to_string(index);
    if (auto n = r.find("name")) mesh.name = n->string();
    mesh.geometry = std::make_shared<const clip::TriangleMesh>(clip::meshFromJson(r.at("mesh"), sceneFile.parent_path()));
    if (auto p = r.find("position_mm")) mesh.pose.position = p->vec3(-1e5, 1e5);
    if (auto rot = r.find("rotation_deg")) {
        glm::dvec3 a = glm::radians(rot->vec3(-3600, 3600));
        mesh.pose.orientation = glm::angleAxis(a.z, glm::dvec3(0, 0, 1)) * glm::angleAxis(a.y, glm::dvec3(0, 1, 0)) *
                                glm::angleAxis(a.x, glm::dvec3(1, 0, 0));
    }
    if (auto c = r.find("clips_tubes")) mesh.clipsTubes = c->boolean();
    if (auto s = r.find("scale")) {
        if (s->isNumber()) {
            mesh.scale = glm::dvec3(s->number(1e-6, 1e6));
        } else {
            mesh.scale = s->vec3(1e-6, 1e6);
        }
    }
    r.finish();
    return mesh;
}

SceneTubes parseTubes(const JsonReader& r, const fs::path& sceneFile) {
    SceneTubes t;
    t.path = resolvePath(sceneFile, r.at("path").string());
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
        throw InputError(sceneFile.string(), r.path() + ".scalar", "the name of a per-point scalar for \"color\": \"scalar\"", "nothing");
    t.name = fileStem(t.path);
    if (auto v = r.find("name")) t.name = v->string();
    if (auto v = r.find("protected")) t.protectedBundle = v->boolean();
    r.finish();
    return t;
}

// Ids (numbers) or names (strings), kept as text until the table is read.
std::vector<std::string> idsOrNames(const JsonReader& r) {
    std::vector<std::string> out;
    for (const JsonReader& e : r.elements())
        out.push_back(e.isNumber() ? std::to_string(e.integer(0, 65535)) : e.string());
    return out;
}

SceneLabels parseLabels(const JsonReader& r, const fs::path& sceneFile) {
    SceneLabels l;
    l.jsonPath = r.path();
    l.path = resolvePath(sceneFile, r.at("path").string());
    l.name = fileStem(l.path);
    if (auto v = r.find("name")) l.name = v->string();
    if (auto v = r.find("table")) l.table = resolvePath(sceneFile, v->string());
    if (auto v = r.find("colors")) l.colors = resolvePath(sceneFile, v->string());
    if (auto v = r.find("opacity")) l.opacity = v->number(0, 1);
    if (auto v = r.find("show")) {
        if (v->isArray()) {
            l.show = SceneLabels::Show::Listed;
            l.shown = idsOrNames(*v);
        } else {
            std::string how = v->oneOf({"all", "protected", "none"});
            l.show = how == "all" ? SceneLabels::Show::All : how == "none" ? SceneLabels::Show::None : SceneLabels::Show::Protected;
        }
    }
    if (auto v = r.find("protected")) l.protectedLabels = idsOrNames(*v);
    if (auto v = r.find("protected_color")) l.protectedColor = v->vec3(0, 1);
    r.finish();
    return l;
}

ReportSpec parseReport(const JsonReader& r) {
    ReportSpec spec;
    if (auto v = r.find("tissue")) {
        std::string t = v->oneOf({"opacity", "labels", "all"});
        spec.tissue = t == "opacity" ? ReportSpec::Tissue::Opacity : t == "labels" ? ReportSpec::Tissue::Labels : ReportSpec::Tissue::All;
    }
    if (auto v = r.find("opacity_threshold")) spec.opacityThreshold = v->number(0, 1);
    if (auto v = r.find("tissue_labels")) spec.tissueLabels = idsOrNames(*v);
    if (auto v = r.find("tract_step_mm")) spec.tractStepMm = v->number(0.01, 10);
    r.finish();
    return spec;
}

void parseTubeRendering(const JsonReader& r, Scene& scene) {
    TubeShading& t = scene.tubeShading;
    if (auto v = r.find("mode")) scene.tubesAsLines = v->oneOf({"tubes", "lines"}) == "lines";
    if (auto v = r.find("build")) scene.tubesBuiltOnGpu = v->oneOf({"cpu", "gpu"}) == "gpu";
    if (auto v = r.find("geometry_opacity")) t.geometryOpacity = v->number(0, 1);
    if (auto v = r.find("vicinity_distance_mm")) t.vicinityDistanceMm = v->number(0, 1000);
    if (auto v = r.find("vicinity_samples")) t.vicinitySamples = v->integer(1, 256);
    if (auto v = r.find("depth_bias_mm")) t.depthBiasMm = v->number(0, 100);
    if (auto v = r.find("line_diffuse_exponent")) t.lineDiffuseExponent = v->number(0.1, 20);
    if (auto m = r.find("material")) io::readMaterial(*m, t.material);
    r.finish();
}

DosSettings parseDos(const JsonReader& r) {
    DosSettings d;
    if (auto v = r.find("cone_angle_deg")) d.coneAngleDeg = v->number(0, 89.9);
    if (auto v = r.find("grid")) d.gridSize = v->integer(1, 16);
    if (auto v = r.find("slice_distance_mm")) d.sliceDistanceMm = v->number(0, 100);
    if (auto v = r.find("ambient")) d.ambientRadiance = v->number(0, 100);
    r.finish();
    return d;
}

IsmosSettings parseIsmos(const JsonReader& r) {
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

}  // namespace

Scene parseScene(std::string_view text, const fs::path& path) {
    Scene scene;
    scene.file = path;
    nlohmann::json json = parseJson(text, path.string());
    JsonReader root(json, path.string());
    if (!root.isObject()) root.fail("a JSON object describing a scene");

    parseVolume(root.at("volume"), scene);

    JsonReader tf = root.at("transfer_function");
    if (tf.isString()) {
        fs::path tfPath = resolvePath(path, tf.string());
        scene.transferFunction = io::readTransferFunction(tfPath);
        scene.transferFunctionSource = tfPath.string();
    } else if (tf.isObject()) {
        scene.transferFunction = io::parseTransferFunctionJson(tf.json(), path.string(), "transfer_function");
        scene.transferFunctionSource = path.string() + ": transfer_function";
    } else {
        tf.fail("a transfer-function file name (.json or .vp) or an inline transfer function object");
    }

    if (auto c = root.find("camera")) parseCamera(*c, scene.camera);
    std::vector<IsmosLightShape> lightShapes;   // ISMOS per-light keys, kept beside the lights
    if (auto s = root.find("shading")) {
        auto mode = parseShadingMode(s->isString() ? s->string() : "");
        if (!mode) s->fail("one of " + shadingModeList());
        scene.shading = *mode;
    }
    if (auto lights = root.find("lights")) {
        scene.lights.clear();
        for (const JsonReader& l : lights->elements(0, 4)) {
            IsmosLightShape shape;
            scene.lights.push_back(parseLight(l, shape));
            lightShapes.push_back(shape);
        }
    }
    if (auto image = root.find("image")) {
        if (auto w = image->find("width")) scene.imageSize.x = w->integer(1, 16384);
        if (auto h = image->find("height")) scene.imageSize.y = h->integer(1, 16384);
        if (auto b = image->find("background")) scene.background = b->vec4(0, 1);
        image->finish();
    }
    if (auto rc = root.find("raycast")) {
        if (auto s = rc->find("step_mm")) scene.raycast.stepMm = s->number(0, 100);
        if (auto e = rc->find("early_termination")) scene.raycast.earlyTerminationAlpha = e->number(0.5, 1.0);
        if (auto j = rc->find("jitter_seed")) scene.raycast.jitterSeed = static_cast<std::uint32_t>(j->unsignedInteger(UINT32_MAX));
        if (auto k = rc->find("skip_empty_space")) scene.raycast.skipEmptySpace = k->boolean();
        if (auto faces = rc->find("cut_faces")) {
            CutFaceSettings& f = scene.raycast.cutFace;
            if (auto e = faces->find("enabled")) f.enabled = e->boolean();
            if (auto d = faces->find("normal_depth_mm")) f.normalDepthMm = d->number(0.01, 100);
            faces->finish();
        }
        rc->finish();
    }
    if (auto lao = root.find("ambient_occlusion")) scene.lao = parseLao(*lao);
    if (auto meshes = root.find("clip_meshes")) {
        std::vector<JsonReader> list = meshes->elements(0, clip::kMaxClipMeshes);
        for (std::size_t i = 0; i < list.size(); ++i) scene.clipMeshes.push_back(parseClipMesh(list[i], path, i));
    }
    if (auto tubes = root.find("tubes"))
        for (const JsonReader& t : tubes->elements(0, 64)) scene.tubes.push_back(parseTubes(t, path));
    if (auto r = root.find("tube_rendering")) parseTubeRendering(*r, scene);
    if (auto d = root.find("dos")) scene.dos = parseDos(*d);
    if (auto i = root.find("ismos")) scene.ismos = parseIsmos(*i);
    scene.ismos.lightShapes = lightShapes;
    if (auto labels = root.find("labels"))
        for (const JsonReader& l : labels->elements(0, 8)) scene.labels.push_back(parseLabels(l, path));
    if (auto r = root.find("report")) scene.report = parseReport(*r);
    if (scene.report.tissue == ReportSpec::Tissue::Labels && scene.labels.empty())
        throw InputError(path.string(), "report.tissue", "\"opacity\" or \"all\" in a scene without labels", "\"labels\"");
    root.finish();
    return scene;
}

Scene loadScene(const fs::path& path) {
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    return parseScene(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path);
}

OrbitCamera resolveCamera(const CameraSpec& spec, const VolumeGeometry& geometry) {
    OrbitCamera camera;
    camera.fovYDeg = spec.fovYDeg;
    camera.azimuthDeg = spec.azimuthDeg;
    camera.elevationDeg = spec.elevationDeg;
    double radius = geometry.boundingRadiusMm();
    camera.fit(spec.target.value_or(geometry.worldCenter()), radius);
    if (spec.distanceMm) {
        camera.distanceMm = *spec.distanceMm;
        camera.nearMm = std::max(0.1, camera.distanceMm - 4.0 * radius);
        camera.farMm = camera.distanceMm + 4.0 * radius;
    }
    return camera;
}

FrameDescription initialFrame(const Scene& scene, const VolumeGeometry& geometry) {
    FrameDescription frame;
    frame.camera = resolveCamera(scene.camera, geometry);
    frame.size = scene.imageSize;
    frame.shading = scene.shading;
    frame.lights = scene.lights;
    frame.raycast = scene.raycast;
    frame.dos = scene.dos;
    frame.ismos = scene.ismos;
    return frame;
}

}  // namespace curette
