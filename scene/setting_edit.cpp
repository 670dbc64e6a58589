#include "scene/setting_edit.h"

#include "base/enum_table.h"
#include "base/error.h"

namespace curette {

namespace {

constexpr SettingInfo kSettings[] = {
    {Setting::Shading, "shading", SettingTarget::None, nullptr},
    {Setting::TransferFunction, "transfer_function", SettingTarget::None, nullptr},
    {Setting::AmbientOcclusion, "ambient_occlusion", SettingTarget::None, nullptr},
    {Setting::Raycast, "raycast", SettingTarget::None, nullptr},
    {Setting::Dos, "dos", SettingTarget::None, nullptr},
    {Setting::Ismos, "ismos", SettingTarget::None, nullptr},
    {Setting::Light, "lights", SettingTarget::Light, "light"},
    {Setting::LightAdd, "lights.add", SettingTarget::None, nullptr},
    {Setting::LightRemove, "lights.remove", SettingTarget::Light, "light"},
    {Setting::TubeRendering, "tube_rendering", SettingTarget::None, nullptr},
    {Setting::Tubes, "tubes", SettingTarget::Tubes, "tube"},
    {Setting::MeshAdd, "clip_meshes.add", SettingTarget::Mesh, "mesh"},
    {Setting::MeshRemove, "clip_meshes.remove", SettingTarget::Mesh, "mesh"},
    {Setting::MeshShape, "clip_meshes.mesh", SettingTarget::Mesh, "mesh"},
    {Setting::MeshScale, "clip_meshes.scale", SettingTarget::Mesh, "mesh"},
    {Setting::MeshClipsTubes, "clip_meshes.clips_tubes", SettingTarget::Mesh, "mesh"},
    {Setting::MeshPose, "clip_meshes.pose", SettingTarget::Mesh, "mesh"},
    {Setting::ClipMeshDisplay, "clip_mesh_display", SettingTarget::None, nullptr},
};
static_assert(rowsInEnumOrder(kSettings, &SettingInfo::setting, Setting::Count));

}  // namespace

const SettingInfo& settingInfo(Setting setting) { return kSettings[static_cast<std::size_t>(setting)]; }

std::optional<Setting> settingFromKey(std::string_view key) {
    for (const SettingInfo& info : kSettings)
        if (key == info.key) return info.setting;
    return std::nullopt;
}

std::string settingKeyList() {
    std::string out;
    for (const SettingInfo& info : kSettings) out += std::string(out.empty() ? "" : ", ") + "\"" + info.key + "\"";
    return out;
}

SettingValue readSettingValue(const SettingEdit& edit, const std::string& source, const std::string& keyPath,
                              const std::filesystem::path& directory, const SceneTubes& tubeDefaults) {
    JsonReader r(edit.value, source, keyPath);
    switch (edit.setting) {
        case Setting::Shading: return readShading(r);
        case Setting::TransferFunction: return readInlineTransferFunction(r);
        case Setting::AmbientOcclusion: return readLao(r);
        case Setting::Raycast: return readRaycast(r);
        case Setting::Dos: return readDos(r);
        case Setting::Ismos: return readIsmos(r);
        case Setting::Light:
        case Setting::LightAdd: {
            LightValue v;
            v.light = readLight(r, v.shape);
            return v;
        }
        case Setting::LightRemove:
            if (!edit.value.is_null()) r.fail("null (removing a light takes no value)");
            return std::monostate{};
        case Setting::TubeRendering: return readTubeRendering(r);
        case Setting::Tubes: {
            SceneTubes t = tubeDefaults;
            t.settings = TubeSettings{};
            t.protectedBundle = false;
            readTubeKeys(r, t, source);
            return t;
        }
        case Setting::MeshAdd: return readClipMesh(r, directory, static_cast<std::size_t>(std::max(edit.target, 0)));
        case Setting::MeshRemove:
            if (!edit.value.is_null()) r.fail("null (removing a mesh takes no value)");
            return std::monostate{};
        case Setting::MeshShape: return MeshGeometry{readMeshGeometry(r, directory)};
        case Setting::MeshScale: return readMeshScale(r);
        case Setting::MeshClipsTubes: return r.boolean();
        case Setting::MeshPose: return readMeshPose(r);
        case Setting::ClipMeshDisplay: return readClipMeshDisplay(r);
        case Setting::Count: break;
    }
    throw std::logic_error("readSettingValue: no such setting");
}

nlohmann::ordered_json settingEditJson(const SettingEdit& edit) {
    const SettingInfo& info = settingInfo(edit.setting);
    nlohmann::ordered_json j;
    j["setting"] = info.key;
    if (info.targetKey && edit.target >= 0) j[info.targetKey] = edit.target;
    j["value"] = nlohmann::ordered_json::parse(edit.value.dump());
    return j;
}

SettingEdit readSettingEdit(const JsonReader& r, const std::filesystem::path& directory) {
    if (!r.isObject()) r.fail("an edit {\"setting\": KEY, \"value\": ...}");
    SettingEdit edit;
    JsonReader key = r.at("setting");
    std::optional<Setting> setting = settingFromKey(key.isString() ? key.string() : "");
    if (!setting) key.fail("one of " + settingKeyList());
    edit.setting = *setting;
    const SettingInfo& info = settingInfo(edit.setting);
    if (info.targetKey) {
        int limit = info.target == SettingTarget::Light ? 63 : info.target == SettingTarget::Tubes ? 63 : 1 << 20;
        edit.target = r.at(info.targetKey).integer(0, limit);
    }
    JsonReader value = r.at("value");
    edit.value = value.json();
    readSettingValue(edit, r.file(), value.path(), directory);   // strict: a bad value is an error here
    r.finish();
    return edit;
}

}  // namespace curette
