#include "mesh/mesh_description.h"

#include "mesh/gltf_mesh.h"
#include "mesh/primitives.h"

namespace curette::clip {

TriangleMesh meshFromJson(const JsonReader& r, const std::filesystem::path& sceneDirectory) {
    std::string shape = r.at("shape").oneOf({"sphere", "box", "cylinder", "cone", "capsule", "torus", "gltf"});
    auto resolution = [&](int fallback, int minimum, int maximum) {
        auto res = r.find("resolution");
        return res ? res->integer(minimum, maximum) : fallback;
    };
    auto length = [&](const char* key) { return r.at(key).number(1e-6, 1e6); };
    TriangleMesh mesh;
    if (shape == "sphere") mesh = makeSphere(length("radius_mm"), resolution(4, 0, 7));
    else if (shape == "box") mesh = makeBox(r.at("size_mm").vec3(1e-6, 1e6));
    else if (shape == "cylinder") mesh = makeCylinder(length("radius_mm"), length("height_mm"), resolution(64, 3, 4096));
    else if (shape == "cone") mesh = makeCone(length("radius_mm"), length("height_mm"), resolution(64, 3, 4096));
    else if (shape == "capsule") mesh = makeCapsule(length("radius_mm"), r.at("length_mm").number(0, 1e6), resolution(48, 4, 4096));
    else if (shape == "torus") {
        int segments = resolution(96, 3, 4096);
        mesh = makeTorus(length("major_radius_mm"), length("minor_radius_mm"), segments, std::max(3, segments / 2));
    } else {
        std::filesystem::path path = r.at("path").string();
        if (path.is_relative()) path = sceneDirectory / path;
        double unitsToMm = 1000.0;
        if (auto units = r.find("units")) unitsToMm = units->oneOf({"m", "mm"}) == "mm" ? 1.0 : 1000.0;
        mesh = loadGltf(path, unitsToMm);
    }
    r.finish();
    return mesh;
}

}  // namespace curette::clip
