#include "scene/scene_labels.h"

#include "io/label_table.h"
#include "io/volume_file.h"
#include "base/error.h"

#include <algorithm>
#include <charconv>
#include <filesystem>

namespace curette {

namespace fs = std::filesystem;

namespace {

// The table beside a label volume, the most specific name first: X.nii.gz -> X.nii.gz.txt, X.nii.txt (what
// the mricron atlases ship), X.txt, and the same with .ctbl.
std::optional<fs::path> siblingTable(const fs::path& volume) {
    for (const std::string& stem : fileNameStems(volume))
        for (const char* ext : {".txt", ".ctbl"})
            if (fs::path candidate = volume.parent_path() / (stem + ext); fs::is_regular_file(candidate)) return candidate;
    return std::nullopt;
}

}  // namespace

std::vector<int> resolveLabelIds(const std::vector<std::string>& idsOrNames, const LabelTable& table, const std::string& sceneFile,
                                 const std::string& field) {
    std::vector<int> ids;
    for (std::size_t i = 0; i < idsOrNames.size(); ++i) {
        const std::string& text = idsOrNames[i];
        int id = -1;
        auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), id);
        bool numeric = ec == std::errc() && end == text.data() + text.size();
        if (!numeric) {
            const LabelEntry* entry = table.findName(text);
            if (!entry)
                throw InputError(sceneFile, field + "[" + std::to_string(i) + "]", "an id or a label name of " + table.source,
                                 "\"" + text + "\"");
            id = entry->id;
        } else if (!table.find(id)) {
            throw InputError(sceneFile, field + "[" + std::to_string(i) + "]", "an id that " + table.source + " has", text);
        }
        ids.push_back(id);
    }
    return ids;
}

std::vector<LoadedLabelSet> loadSceneLabels(const Scene& scene, const VolumeData& scan) {
    std::vector<LoadedLabelSet> sets;
    for (const SceneLabels& spec : scene.labels) {
        if (!fs::exists(spec.path))
            throw InputError(scene.file.string(), spec.jsonPath + ".path", "an existing label volume", "\"" + spec.path.string() + "\"");
        LoadedLabelSet set;
        set.name = spec.name;
        set.source = spec.path.string();
        set.opacity = spec.opacity;
        VolumeData volume = io::readVolume(spec.path);
        set.volumeFiles = volume.files;
        LabelMap own = labelMapFromVolume(volume);
        std::optional<fs::path> tablePath = spec.table ? spec.table : siblingTable(spec.path);
        set.tableFile = tablePath;
        set.colorsFile = spec.colors;
        if (tablePath) set.table = io::readLabelTable(*tablePath);
        else set.table.source = spec.path.string() + " (no table: names generated)";
        if (spec.colors) {
            LabelTable lut = io::readLut(*spec.colors);
            for (LabelEntry& e : set.table.entries)
                if (const LabelEntry* c = lut.find(e.id)) e.rgba = c->rgba;
        }
        io::addMissingLabels(set.table, own);
        set.onScanGrid = resampleNearest(own, scan.dims, scan.indexToWorld);
        set.protectedIds = resolveLabelIds(spec.protectedLabels, set.table, scene.file.string(), spec.jsonPath + ".protected");
        if (spec.protectedColor)
            for (LabelEntry& e : set.table.entries)
                if (std::find(set.protectedIds.begin(), set.protectedIds.end(), e.id) != set.protectedIds.end())
                    e.rgba = glm::dvec4(*spec.protectedColor, 1.0);
        int maxId = 0;
        for (const LabelEntry& e : set.table.entries) maxId = std::max(maxId, e.id);
        set.shown.assign(std::size_t(maxId) + 1, false);
        std::vector<int> listed;
        if (spec.show == SceneLabels::Show::Listed) listed = resolveLabelIds(spec.shown, set.table, scene.file.string(), spec.jsonPath + ".show");
        if (spec.show == SceneLabels::Show::Protected) listed = set.protectedIds;
        if (spec.show == SceneLabels::Show::All) std::fill(set.shown.begin(), set.shown.end(), true);
        for (int id : listed) set.shown[std::size_t(id)] = true;
        set.shown[0] = false;
        sets.push_back(std::move(set));
    }
    return sets;
}

LabelRendering labelRendering(const std::vector<LoadedLabelSet>& sets) {
    LabelRendering out;
    bool anyShown = false;
    for (const LoadedLabelSet& s : sets) anyShown = anyShown || (s.opacity > 0 && std::find(s.shown.begin(), s.shown.end(), true) != s.shown.end());
    if (!anyShown) return out;
    std::vector<std::size_t> offsets;
    std::size_t next = 0;
    for (const LoadedLabelSet& s : sets) {
        offsets.push_back(next);
        next += s.shown.size();
    }
    if (next > 65536) throw InputError(sets.back().source, "label ids", "at most 65536 label ids over all label sets", std::to_string(next));
    out.styles.assign(next, glm::vec4(0.0f));
    for (std::size_t s = 0; s < sets.size(); ++s)
        for (const LabelEntry& e : sets[s].table.entries)
            if (e.id > 0 && sets[s].shown[std::size_t(e.id)])
                out.styles[offsets[s] + std::size_t(e.id)] = glm::vec4(glm::vec3(e.rgba), static_cast<float>(sets[s].opacity));
    std::size_t voxels = sets.front().onScanGrid.ids.size();
    out.ids.assign(voxels, 0);
    for (std::size_t v = 0; v < voxels; ++v)
        for (std::size_t s = 0; s < sets.size(); ++s) {
            std::uint16_t id = sets[s].onScanGrid.ids[v];
            if (id != 0 && sets[s].shown[id]) {
                out.ids[v] = static_cast<std::uint16_t>(offsets[s] + id);
                break;
            }
        }
    return out;
}

}  // namespace curette
