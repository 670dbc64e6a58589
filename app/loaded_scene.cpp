#include "app/loaded_scene.h"

#include "base/error.h"

namespace curette {

LoadedScene loadSceneWithVolume(const std::filesystem::path& scenePath) {
    LoadedScene loaded;
    loaded.scene = loadScene(scenePath);
    try {
        loaded.volume = io::readVolume(loaded.scene.volumePath, loaded.scene.volumeOptions);
    } catch (const InputError& e) {
        // Say which scene key led here when the volume file itself is missing.
        if (!std::filesystem::exists(loaded.scene.volumePath))
            throw InputError(scenePath.string(), "volume.path", "an existing volume file",
                             "\"" + loaded.scene.volumePath.string() + "\", which does not exist");
        throw;
    }
    return loaded;
}

void configureRenderer(const Scene& scene, Renderer& renderer) {
    renderer.setLaoSettings(scene.lao);
    clip::ClipMeshSet& clip = renderer.clipMeshes();
    clip.clear();
    for (const SceneClipMesh& mesh : scene.clipMeshes) {
        int index = clip.add(mesh.geometry, mesh.scale, mesh.pose, mesh.name);
        clip.setClipsTubes(index, mesh.clipsTubes);
    }
}

ShadingMode parseShadingOption(const std::string& option, const std::string& text) {
    auto mode = parseShadingMode(text);
    if (!mode) throw InputError("<command line>", "--" + option, "one of " + shadingModeList(), "\"" + text + "\"");
    return *mode;
}

void applyOverrides(const FrameOverrides& o, FrameDescription& frame) {
    if (o.size) frame.size = *o.size;
    if (o.shading) frame.shading = *o.shading;
    if (o.azimuthDeg) frame.camera.azimuthDeg = *o.azimuthDeg;
    if (o.elevationDeg) frame.camera.elevationDeg = *o.elevationDeg;
}

}  // namespace curette
