#pragma once
// A scene with its volume read from disk: the common first step of render, view, bench and replay.

#include "scene/scene.h"
#include "scene/scene_labels.h"
#include "render/renderer.h"
#include "base/tractogram.h"
#include "base/volume.h"

namespace curette {

struct LoadedScene {
    Scene scene;
    VolumeData volume;
    std::vector<Tractogram> tracts;   // one per scene.tubes entry
    std::vector<LoadedLabelSet> labels;  // one per scene.labels entry, on the scan grid
    // The scene's drilled removal ("removal", session/removal_file.h), on the scan grid; null: none. Commands
    // drill on a copy (SessionStep::attachRemoval), so this stays the scene's.
    std::shared_ptr<const plan::RemovalVolume> removal;
};

LoadedScene loadSceneWithVolume(const std::filesystem::path& scenePath);

// Hands the scene's labels, its removal, and by syncRenderer (session/session_step.h, the path edits take too) its LAO
// settings, clip meshes and tubes, to a renderer made for its volume and transfer function: every command that
// renders a scene goes through here, so they all render the same thing.
void configureRenderer(const LoadedScene& loaded, Renderer& renderer);

// Every bundle of a scene's tubes in one vertex set (tubes, or lines for the illuminated-lines mode), and
// their shading (the depth a tube fills in the slab pass is the diameter of the largest): what
// configureRenderer and the session step (after a tube edit) hand the renderer.
TubeVertices sceneTubeVertices(const std::vector<SceneTubes>& tubes, bool lines, const std::vector<Tractogram>& tracts);
TubeShading sceneTubeShading(const std::vector<SceneTubes>& tubes, const TubeShading& shading);
// Every bundle's swept rings, for tubes expanded on the GPU ("build": "gpu", render/passes/gpu_tube_builder.h).
TubeRings sceneTubeRings(const std::vector<SceneTubes>& tubes, const std::vector<Tractogram>& tracts);
// Every bundle's swept points, for impostor tubes ("build": "impostor", render/model/tube_impostors.h).
TubeImpostors sceneTubeImpostors(const std::vector<SceneTubes>& tubes, const std::vector<Tractogram>& tracts);
// The scene's tubes into the renderer as `rendering` says (lines, CPU-built, GPU-built or impostor tubes).
void setSceneTubes(Renderer& renderer, const std::vector<SceneTubes>& tubes, const TubeRendering& rendering,
                   const std::vector<Tractogram>& tracts);

// Applies the --size/--shading/--azimuth/--elevation overrides shared by render-like commands.
struct FrameOverrides {
    std::optional<glm::ivec2> size;
    std::optional<ShadingMode> shading;
    std::optional<double> azimuthDeg, elevationDeg;
};
void applyOverrides(const FrameOverrides& overrides, FrameDescription& frame);
ShadingMode parseShadingOption(const std::string& option, const std::string& text);
// A comma-separated list of shading modes (a command's --option), each once, in the order given.
std::vector<ShadingMode> parseShadingList(const std::string& option, const std::string& text);

}  // namespace curette
