#pragma once
// A scene with its volume read from disk: the common first step of render, view, bench and replay.

#include "app/scene.h"
#include "app/scene_labels.h"
#include "render/renderer.h"
#include "base/tractogram.h"
#include "base/volume.h"

namespace curette {

struct LoadedScene {
    Scene scene;
    VolumeData volume;
    std::vector<Tractogram> tracts;   // one per scene.tubes entry
    std::vector<LoadedLabelSet> labels;  // one per scene.labels entry, on the scan grid
};

LoadedScene loadSceneWithVolume(const std::filesystem::path& scenePath);

// Hands the scene's LAO settings, labels, clip meshes (through the session step's one path, app/session_step.h) and
// tubes to a renderer made for its volume: every command that renders a scene goes through here, so they all
// render the same thing.
void configureRenderer(const LoadedScene& loaded, Renderer& renderer);

// The pieces configureRenderer hands the renderer for the scene's tubes (bench tracts times them one by one):
// the shading (its thickness twice the largest radius), every entry's swept rings (for "build": "gpu"), and
// every entry's vertices built on the CPU (tubes, or illuminated lines in "mode": "lines").
TubeShading sceneTubeShading(const Scene& scene);
TubeRings sweepSceneTubes(const LoadedScene& loaded);
TubeVertices buildSceneTubeVertices(const LoadedScene& loaded);

// Applies the --size/--shading/--azimuth/--elevation overrides shared by render-like commands.
struct FrameOverrides {
    std::optional<glm::ivec2> size;
    std::optional<ShadingMode> shading;
    std::optional<double> azimuthDeg, elevationDeg;
};
void applyOverrides(const FrameOverrides& overrides, FrameDescription& frame);
ShadingMode parseShadingOption(const std::string& option, const std::string& text);

}  // namespace curette
