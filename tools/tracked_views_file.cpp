#include "tools/tracked_views_file.h"

#include "base/error.h"
#include "base/json_reader.h"
#include "base/atomic_file.h"

namespace curette {

TrackedViewsFile readTrackedViews(const std::filesystem::path& path) {
    const std::string file = path.string();
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    nlohmann::json json = parseJson(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), file);
    JsonReader root(json, file);
    TrackedViewsFile out;
    out.space = root.at("space").oneOf({"stage", "local"}) == "stage" ? RoomSpace::Stage : RoomSpace::Local;
    glm::dvec2 size = root.at("recommended_size").vec2(1, 16384);
    out.recommendedSize = glm::ivec2(size);
    if (glm::dvec2(out.recommendedSize) != size) root.at("recommended_size").fail("two whole numbers of pixels");
    std::vector<JsonReader> views = root.at("views").elements(2, 2);
    for (std::size_t eye = 0; eye < 2; ++eye) {
        const JsonReader& v = views[eye];
        TrackedView& t = out.views[eye];
        t.positionM = v.at("position_m").vec3(-1e4, 1e4);
        glm::dvec4 q = v.at("orientation").vec4(-1.0001, 1.0001);
        if (glm::length(q) < 0.99 || glm::length(q) > 1.01) v.at("orientation").fail("a unit quaternion [x, y, z, w]");
        t.orientation = glm::normalize(glm::dquat(q.w, q.x, q.y, q.z));
        std::vector<double> fov = v.at("fov_rad").numbers(4, -1.57, 1.57);
        t.fov = {fov[0], fov[1], fov[2], fov[3]};
        if (!(t.fov.angleRight > t.fov.angleLeft && t.fov.angleUp > t.fov.angleDown))
            v.at("fov_rad").fail("[left, right, up, down] radians with left < right and down < up");
        v.find("submitted_fov_rad");
        v.find("image_rect");
        v.finish();
    }
    if (auto volume = root.find("volume")) {
        out.volumeCentreRoomM = volume->at("centre_m").vec3(-1e4, 1e4);
        glm::dvec4 q = volume->at("turn").vec4(-1.0001, 1.0001);
        if (glm::length(q) < 0.99 || glm::length(q) > 1.01) volume->at("turn").fail("a unit quaternion [x, y, z, w]");
        out.volumeTurnRoom = glm::dquat(q.w, q.x, q.y, q.z);   // as written: the recorded bits, not renormalised
        if (auto scale = volume->find("scale")) out.volumeScale = scale->number(1e-3, 1e3);
        volume->finish();
    }
    root.finish();
    return out;
}

RoomAnchor viewsAnchor(const TrackedViewsFile& file, const VolumeGeometry& geometry) {
    RoomAnchor anchor = tableAnchor(geometry, file.space);
    if (file.volumeCentreRoomM) {
        anchor.volumeCentreRoomM = *file.volumeCentreRoomM;
        anchor.volumeTurnRoom = file.volumeTurnRoom;
        anchor.volumeScale = file.volumeScale;
    }
    return anchor;
}

}  // namespace curette
