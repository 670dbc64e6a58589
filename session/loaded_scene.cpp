#include "session/loaded_scene.h"

#include "io/tract_file.h"
#include "session/removal_file.h"
#include "session/session_step.h"
#include "base/error.h"
#include "base/log.h"
#include "base/progress.h"

#include <algorithm>

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
    for (const SceneTubes& t : loaded.scene.tubes) loaded.tracts.push_back(io::readTractogram(t.path));
    loaded.labels = loadSceneLabels(loaded.scene, loaded.volume);
    if (loaded.scene.removalPath)
        loaded.removal = readRemovalFile(*loaded.scene.removalPath, loaded.volume.dims, loaded.volume.indexToWorld, scenePath.string(), "removal");
    return loaded;
}

void configureRenderer(const LoadedScene& loaded, Renderer& renderer) {
    LabelRendering labels = labelRendering(loaded.labels);
    if (!labels.ids.empty()) renderer.setLabels(std::make_unique<LabelOverlay>(loaded.volume.dims, labels.ids, labels.styles));
    // The scene's settings by the session step's path; the renderer was made with its transfer function.
    RendererSync synced{.transferFunction = RendererSync::sceneSettings().transferFunction};
    syncRenderer(InteractionState::fromScene(loaded.scene), renderer, loaded.tracts, synced);
    if (loaded.removal) renderer.setRemoval(loaded.removal);
}

namespace {

double streamlineCount(const std::vector<Tractogram>& tracts) {
    double n = 0;
    for (const Tractogram& t : tracts) n += double(t.streamlineCount());
    return n;
}

void logSkipped(const SceneTubes& tubes, const TubeBuildStats& stats) {
    if (stats.skippedSinglePoint)
        log::info(tubes.path.string() + ": " + std::to_string(stats.skippedSinglePoint) + " one-point streamlines skipped");
}

}  // namespace

void setSceneTubes(Renderer& renderer, const std::vector<SceneTubes>& tubes, const TubeRendering& rendering,
                   const std::vector<Tractogram>& tracts) {
    if (tubes.empty()) {
        renderer.clearTubes();
        return;
    }
    TubeShading shading = sceneTubeShading(tubes, rendering.shading);
    if (!rendering.lines && rendering.build == TubeBuild::Gpu) renderer.setTubeRings(sceneTubeRings(tubes, tracts), shading);
    else if (!rendering.lines && rendering.build == TubeBuild::Impostor) renderer.setTubeImpostors(sceneTubeImpostors(tubes, tracts), shading);
    else renderer.setTubes(sceneTubeVertices(tubes, rendering.lines, tracts), shading);
}

namespace {
// Every tube entry swept by `sweep` (sweepTubeRings or sweepTubeImpostors) into one set, with one progress bar.
template <class Set, class Sweep>
Set sweepEachEntry(const std::vector<SceneTubes>& tubes, const std::vector<Tractogram>& tracts, Sweep sweep) {
    Set all;
    Progress progress("sweeping tubes", streamlineCount(tracts));
    for (std::size_t i = 0; i < tubes.size(); ++i) {
        TubeBuildStats stats;
        Set one = sweep(tracts[i], tubes[i].settings, &stats, &progress);
        logSkipped(tubes[i], stats);
        if (i == 0) all = std::move(one);
        else all.append(one);
    }
    return all;
}
}  // namespace

TubeImpostors sceneTubeImpostors(const std::vector<SceneTubes>& tubes, const std::vector<Tractogram>& tracts) {
    return sweepEachEntry<TubeImpostors>(tubes, tracts, sweepTubeImpostors);
}

TubeRings sceneTubeRings(const std::vector<SceneTubes>& tubes, const std::vector<Tractogram>& tracts) {
    return sweepEachEntry<TubeRings>(tubes, tracts, sweepTubeRings);
}

TubeVertices sceneTubeVertices(const std::vector<SceneTubes>& tubes, bool lines, const std::vector<Tractogram>& tracts) {
    // All entries into one vertex set (tubes, or lines for the illuminated-lines mode).
    TubeVertices all;
    all.lines = lines;
    for (std::size_t i = 0; i < tubes.size(); ++i) {
        TubeBuildStats stats;
        TubeVertices v = lines ? buildIlluminatedLines(tracts[i], tubes[i].settings, &stats) : buildTubes(tracts[i], tubes[i].settings, &stats);
        logSkipped(tubes[i], stats);
        if (i == 0) {
            all = std::move(v);   // no copy of the (large) first set
            continue;
        }
        std::uint32_t base = static_cast<std::uint32_t>(all.positions.size());
        all.positions.insert(all.positions.end(), v.positions.begin(), v.positions.end());
        all.directions.insert(all.directions.end(), v.directions.begin(), v.directions.end());
        all.colors.insert(all.colors.end(), v.colors.begin(), v.colors.end());
        for (std::uint32_t index : v.indices) all.indices.push_back(base + index);
    }
    return all;
}

TubeShading sceneTubeShading(const std::vector<SceneTubes>& tubes, const TubeShading& shading) {
    TubeShading out = shading;
    double radius = 0;
    for (const SceneTubes& t : tubes) radius = std::max(radius, t.settings.radiusMm);
    out.thicknessMm = 2.0 * radius;  // the depth a tube fills behind its surface in the slab pass
    return out;
}

ShadingMode parseShadingOption(const std::string& option, const std::string& text) {
    auto mode = parseShadingMode(text);
    if (!mode) throw InputError("<command line>", "--" + option, "one of " + shadingModeList(), "\"" + text + "\"");
    return *mode;
}

std::vector<ShadingMode> parseShadingList(const std::string& option, const std::string& text) {
    std::vector<ShadingMode> modes;
    std::size_t start = 0;
    while (true) {
        std::size_t comma = text.find(',', start);
        ShadingMode mode = parseShadingOption(option, text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (std::find(modes.begin(), modes.end(), mode) == modes.end()) modes.push_back(mode);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return modes;
}

void applyOverrides(const FrameOverrides& o, FrameDescription& frame) {
    if (o.size) frame.size = *o.size;
    if (o.shading) frame.shading = *o.shading;
    if (o.azimuthDeg) frame.camera.azimuthDeg = *o.azimuthDeg;
    if (o.elevationDeg) frame.camera.elevationDeg = *o.elevationDeg;
}

}  // namespace curette
