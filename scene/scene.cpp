#include "scene/scene.h"

#include "io/transfer_function_file.h"
#include "scene/scene_keys.h"
#include "mesh/mesh_description.h"
#include "mesh/limits.h"
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
    if (auto n = r.find("near_mm")) camera.nearMm = n->number(1e-6, 1e7);
    if (auto f = r.find("far_mm")) camera.farMm = f->number(1e-6, 1e8);
    r.finish();
}

SceneTubes parseTubes(const JsonReader& r, const fs::path& sceneFile) {
    SceneTubes t;
    t.path = resolvePath(sceneFile, r.at("path").string());
    t.name = fileStem(t.path);
    readTubeKeys(r, t, sceneFile.string());
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

}  // namespace

Scene parseScene(std::string_view text, const fs::path& path) {
    Scene scene;
    scene.file = path;
    nlohmann::json json = parseJson(text, path.string());
    JsonReader root(json, path.string());
    if (!root.isObject()) root.fail("a JSON object describing a scene");
    scene.json = json;

    parseVolume(root.at("volume"), scene);

    JsonReader tf = root.at("transfer_function");
    if (tf.isString()) {
        fs::path tfPath = resolvePath(path, tf.string());
        scene.transferFunction = io::readTransferFunction(tfPath);
        scene.transferFunctionSource = tfPath.string();
    } else if (tf.isObject()) {
        scene.transferFunction = readInlineTransferFunction(tf);
        scene.transferFunctionSource = path.string() + ": transfer_function";
    } else {
        tf.fail("a transfer-function file name (.json or .vp) or an inline transfer function object");
    }

    if (auto c = root.find("camera")) parseCamera(*c, scene.camera);
    std::vector<IsmosLightShape> lightShapes;   // ISMOS per-light keys, kept beside the lights
    if (auto s = root.find("shading")) scene.shading = readShading(*s);
    if (auto lights = root.find("lights")) {
        scene.lights.clear();
        for (const JsonReader& l : lights->elements(0, kMaxSceneLights)) {
            IsmosLightShape shape;
            scene.lights.push_back(readLight(l, shape));
            lightShapes.push_back(shape);
        }
    }
    if (auto image = root.find("image")) {
        if (auto w = image->find("width")) scene.imageSize.x = w->integer(1, 16384);
        if (auto h = image->find("height")) scene.imageSize.y = h->integer(1, 16384);
        if (auto b = image->find("background")) scene.background = b->vec4(0, 1);
        image->finish();
    }
    if (auto rc = root.find("raycast")) scene.raycast = readRaycast(*rc);
    if (auto lao = root.find("ambient_occlusion")) scene.lao = readLao(*lao);
    if (auto meshes = root.find("clip_meshes")) {
        std::vector<JsonReader> list = meshes->elements(0, clip::kMaxClipMeshes);
        for (std::size_t i = 0; i < list.size(); ++i) scene.clipMeshes.push_back(readClipMesh(list[i], path.parent_path(), i));
    }
    if (auto d = root.find("clip_mesh_display")) scene.clipMeshDisplay = readClipMeshDisplay(*d);
    if (auto tubes = root.find("tubes"))
        for (const JsonReader& t : tubes->elements(0, 64)) scene.tubes.push_back(parseTubes(t, path));
    if (auto r = root.find("tube_rendering")) {
        TubeRendering t = readTubeRendering(*r);
        scene.tubesAsLines = t.lines;
        scene.tubeBuild = t.build;
        scene.tubeShading = t.shading;
    }
    if (auto d = root.find("dos")) scene.dos = readDos(*d);
    if (auto i = root.find("ismos")) scene.ismos = readIsmos(*i);
    scene.ismos.lightShapes = lightShapes;
    if (auto labels = root.find("labels"))
        for (const JsonReader& l : labels->elements(0, 8)) scene.labels.push_back(parseLabels(l, path));
    if (auto r = root.find("report")) scene.report = parseReport(*r);
    if (auto r = root.find("removal")) {
        std::string file = r->string();
        if (file.empty()) r->fail("a removal file name (NIfTI-1, datatype 1280), relative to the scene's folder");
        scene.removalPath = resolvePath(scene.file, file);
    }
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
    if (spec.nearMm) camera.nearMm = *spec.nearMm;
    if (spec.farMm) camera.farMm = *spec.farMm;
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
