#include "viewer/view_panels.h"

#include "viewer/view_sidebar.h"

#include "io/transfer_function_file.h"
#include "session/plan_scene.h"
#include "session/removal_file.h"
#include "scene/volume_statistics.h"
#include "base/atomic_file.h"
#include "base/error.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>

namespace curette {

std::filesystem::path shippedPresetDirectory() { return std::filesystem::path(CURETTE_ASSET_DIR) / "tf"; }

const char* const kPrimitiveShapes[6] = {"sphere", "box", "cylinder", "cone", "capsule", "torus"};

nlohmann::json primitiveMeshJson(const std::string& shape, double s) {
    if (shape == "box") return {{"shape", "box"}, {"size_mm", {s, s, s}}};
    if (shape == "cylinder" || shape == "cone") return {{"shape", shape}, {"radius_mm", s / 2}, {"height_mm", s}};
    if (shape == "capsule") return {{"shape", "capsule"}, {"radius_mm", s / 4}, {"length_mm", s}};
    if (shape == "torus") return {{"shape", "torus"}, {"major_radius_mm", s / 2}, {"minor_radius_mm", s / 6}};
    return {{"shape", "sphere"}, {"radius_mm", s / 2}};
}

const char* primitiveSizeName(const std::string& shape) {
    if (shape == "box") return "edge (mm)";
    if (shape == "cylinder" || shape == "cone") return "diameter = height (mm)";
    if (shape == "capsule") return "length (mm; diameter a half)";
    if (shape == "torus") return "outer diameter (mm)";
    return "diameter (mm)";
}

namespace {

constexpr int kHistogramBins = 128;

nlohmann::json tfJson(const TransferFunction& tf) { return nlohmann::json::parse(io::writeTransferFunctionJson(tf)); }

SettingEdit edit(Setting setting, nlohmann::json value, int target = -1) { return SettingEdit{setting, target, std::move(value)}; }

// The key's current JSON as an object to change one field of (a scene without the key: an empty object).
nlohmann::json objectOf(const InteractionState& state, const Scene& scene, const std::string& key) {
    nlohmann::json j = state.keyJson(scene, key);
    return j.is_object() ? j : nlohmann::json::object();
}

ImU32 colour(glm::dvec3 c, float alpha = 1.0f) {
    return ImGui::ColorConvertFloat4ToU32(ImVec4(static_cast<float>(c.r), static_cast<float>(c.g), static_cast<float>(c.b), alpha));
}

// A curve of points (x: a value over [c.lo, c.hi], y in [0, 1]) drawn and edited on the canvas `c`, an invisible
// button `id` at the cursor (the caller draws the background first): drag a point to move it (between its
// neighbours), double-click away from the points to add one, right-click one to remove it (one always
// stays). `dragged` is the point being dragged, kept by the caller between frames; `handle` colours a point
// by its value. Returns whether `points` changed. The TF editor's opacity and gradient-opacity canvases.
bool editPointCurve(const char* id, const ViewPanels::Canvas& c, std::vector<TransferFunction::ScalarPoint>& points, int& dragged,
                    const std::function<ImU32(double)>& handle) {
    ImDrawList* draw = ImGui::GetWindowDrawList();
    auto toX = [&](double v) { return c.x + static_cast<float>((v - c.lo) / (c.hi - c.lo)) * c.w; };
    auto toY = [&](double a) { return c.y + static_cast<float>(1.0 - a) * c.h; };
    auto valueAt = [&](float x) { return c.lo + (c.hi - c.lo) * std::clamp((x - c.x) / c.w, 0.0f, 1.0f); };
    auto yAt = [&](float y) { return std::clamp(1.0 - (y - c.y) / c.h, 0.0, 1.0); };
    const std::vector<TransferFunction::ScalarPoint> shown = points;
    for (std::size_t i = 0; i + 1 < shown.size(); ++i)
        draw->AddLine(ImVec2(toX(shown[i].value), toY(shown[i].y)), ImVec2(toX(shown[i + 1].value), toY(shown[i + 1].y)), IM_COL32(240, 240, 240, 255), 1.5f);
    ImGui::InvisibleButton(id, ImVec2(c.w, c.h));
    bool hovered = ImGui::IsItemHovered();
    ImVec2 mouse = ImGui::GetIO().MousePos;
    int nearest = -1;
    float best = 8.0f * 8.0f;
    for (std::size_t i = 0; i < shown.size(); ++i) {
        ImVec2 at(toX(shown[i].value), toY(shown[i].y));
        float dx = at.x - mouse.x, dy = at.y - mouse.y;
        if (dx * dx + dy * dy < best) best = dx * dx + dy * dy, nearest = static_cast<int>(i);
        draw->AddCircleFilled(at, 4.5f, handle(shown[i].value));
        draw->AddCircle(at, 4.5f, IM_COL32(255, 255, 255, 255));
    }
    bool changed = false;
    if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left) && nearest >= 0) dragged = nearest;
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) dragged = -1;
    const int count = static_cast<int>(points.size());
    if (dragged >= 0 && dragged < count && (ImGui::GetIO().MouseDelta.x != 0 || ImGui::GetIO().MouseDelta.y != 0)) {
        auto& p = points[static_cast<std::size_t>(dragged)];
        double left = dragged > 0 ? points[static_cast<std::size_t>(dragged - 1)].value : c.lo;
        double right = dragged + 1 < count ? points[static_cast<std::size_t>(dragged + 1)].value : c.hi;
        p.value = std::clamp(valueAt(mouse.x), left, right);
        p.y = yAt(mouse.y);
        changed = true;
    }
    if (hovered && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left) && nearest < 0) {
        double v = valueAt(mouse.x);
        auto at = std::lower_bound(points.begin(), points.end(), v, [](const auto& p, double x) { return p.value < x; });
        points.insert(at, {v, yAt(mouse.y)});
        changed = true;
    }
    if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Right) && nearest >= 0 && points.size() > 1) {
        points.erase(points.begin() + nearest);
        dragged = -1;
        changed = true;
    }
    return changed;
}

}  // namespace

ViewPanels::ViewPanels(const LoadedScene& loaded, std::filesystem::path presetDirectory) : loaded_(loaded) {
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(presetDirectory, ec)) {
        std::string ext = entry.path().extension().string();
        if (ext == ".json" || ext == ".vp") presets_.push_back(entry.path());
    }
    std::sort(presets_.begin(), presets_.end());
    VolumeStatistics stats = computeStatistics(loaded.volume, kHistogramBins);
    valueMin_ = stats.min;
    valueMax_ = stats.max > stats.min ? stats.max : stats.min + 1;
    double top = 0;
    for (std::uint64_t n : stats.histogram) top = std::max(top, std::log1p(static_cast<double>(n)));
    for (std::uint64_t n : stats.histogram) histogram_.push_back(top > 0 ? std::log1p(static_cast<double>(n)) / top : 0);
    maxGradient_ = maxGradientMagnitude(loaded.volume);
}

std::vector<SettingEdit> ViewPanels::draw(const InteractionState& state, const OrbitCamera& camera, const input::InputPipeline& input) {
    std::vector<SettingEdit> edits;
    if (ImGui::CollapsingHeader("clip meshes (tools)", ImGuiTreeNodeFlags_DefaultOpen)) meshPanel(state, camera, input, edits);
    if (ImGui::CollapsingHeader("transfer function", ImGuiTreeNodeFlags_DefaultOpen)) transferFunctionPanel(state, edits);
    if (ImGui::CollapsingHeader("shading")) shadingPanel(state, edits);
    if (!state.tubes.empty() && ImGui::CollapsingHeader("tubes")) tubePanel(state, edits);
    if (ImGui::CollapsingHeader("lights")) lightPanel(state, edits);
    if (ImGui::CollapsingHeader("scene")) scenePanel(state, camera);
    return edits;
}

// The opacity curve over the histogram (x: data value, y: alpha), the colour points on a bar below it, and
// the gradient-opacity curve below that (x: |gradient|, y: the opacity factor). Drag a point to move it
// (between its neighbours), double-click to add one, right-click to remove one; click a colour point to pick
// its colour.
void ViewPanels::transferFunctionPanel(const InteractionState& state, std::vector<SettingEdit>& edits) {
    const TransferFunction& tf = state.transferFunction;
    TransferFunction changed = tf;
    bool dirty = false;
    double lo = std::min(valueMin_, tf.domainMin()), hi = std::max(valueMax_, tf.domainMax());
    if (!(hi > lo)) hi = lo + 1;

    ImDrawList* draw = ImGui::GetWindowDrawList();
    ImVec2 origin = ImGui::GetCursorScreenPos();
    float width = std::max(200.0f, ImGui::GetContentRegionAvail().x), height = 120.0f, barHeight = 16.0f, gradientHeight = 60.0f;
    canvas_ = {origin.x, origin.y, width, height, lo, hi};
    auto toX = [&](double v) { return origin.x + static_cast<float>((v - lo) / (hi - lo)) * width; };
    auto toY = [&](double a) { return origin.y + static_cast<float>(1.0 - a) * height; };
    auto valueAt = [&](float x) { return lo + (hi - lo) * std::clamp((x - origin.x) / width, 0.0f, 1.0f); };

    draw->AddRectFilled(origin, ImVec2(origin.x + width, origin.y + height), IM_COL32(30, 30, 34, 255));
    // The histogram (log counts) over the volume's value range.
    const double bins = static_cast<double>(histogram_.size());
    for (std::size_t b = 0; b < histogram_.size(); ++b) {
        double v0 = valueMin_ + (valueMax_ - valueMin_) * static_cast<double>(b) / bins;
        double v1 = valueMin_ + (valueMax_ - valueMin_) * static_cast<double>(b + 1) / bins;
        draw->AddRectFilled(ImVec2(toX(v0), toY(histogram_[b])), ImVec2(toX(v1), origin.y + height), IM_COL32(90, 90, 100, 255));
    }
    // The opacity curve, its points coloured by the TF.
    dirty |= editPointCurve("opacity", canvas_, changed.opacity, draggedOpacity_, [&](double v) { return colour(tf.evaluateColor(v)); });
    ImVec2 mouse = ImGui::GetIO().MousePos;

    // The colour bar and its points.
    ImVec2 bar = ImGui::GetCursorScreenPos();
    const int steps = 64;
    for (int k = 0; k < steps; ++k) {
        double v0 = lo + (hi - lo) * k / steps, v1 = lo + (hi - lo) * (k + 1) / steps;
        draw->AddRectFilled(ImVec2(toX(v0), bar.y), ImVec2(toX(v1), bar.y + barHeight), colour(tf.evaluateColor(0.5 * (v0 + v1))));
    }
    ImGui::InvisibleButton("colour", ImVec2(width, barHeight));
    bool barHovered = ImGui::IsItemHovered();
    int nearestColor = -1;
    float bestColor = 6.0f;
    for (std::size_t i = 0; i < tf.color.size(); ++i) {
        float x = toX(tf.color[i].value);
        if (std::abs(x - mouse.x) < bestColor) bestColor = std::abs(x - mouse.x), nearestColor = static_cast<int>(i);
        draw->AddTriangleFilled(ImVec2(x, bar.y + barHeight - 6), ImVec2(x - 5, bar.y + barHeight + 4), ImVec2(x + 5, bar.y + barHeight + 4),
                                static_cast<int>(i) == selectedColor_ ? IM_COL32(255, 220, 0, 255) : IM_COL32(255, 255, 255, 255));
    }
    ImGui::Dummy(ImVec2(width, 6));
    if (barHovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left) && nearestColor >= 0) draggedColor_ = selectedColor_ = nearestColor;
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) draggedColor_ = -1;
    if (draggedColor_ >= 0 && draggedColor_ < static_cast<int>(changed.color.size()) && ImGui::GetIO().MouseDelta.x != 0) {
        double left = draggedColor_ > 0 ? changed.color[static_cast<std::size_t>(draggedColor_ - 1)].value : lo;
        double right = draggedColor_ + 1 < static_cast<int>(changed.color.size()) ? changed.color[static_cast<std::size_t>(draggedColor_ + 1)].value : hi;
        changed.color[static_cast<std::size_t>(draggedColor_)].value = std::clamp(valueAt(mouse.x), left, right);
        dirty = true;
    }
    if (barHovered && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left) && nearestColor < 0) {
        double v = valueAt(mouse.x);
        auto at = std::lower_bound(changed.color.begin(), changed.color.end(), v, [](const auto& p, double x) { return p.value < x; });
        selectedColor_ = static_cast<int>(at - changed.color.begin());
        changed.color.insert(at, {v, tf.evaluateColor(v)});
        dirty = true;
    }
    if (barHovered && ImGui::IsMouseClicked(ImGuiMouseButton_Right) && nearestColor >= 0 && changed.color.size() > 1) {
        changed.color.erase(changed.color.begin() + nearestColor);
        selectedColor_ = -1;
        dirty = true;
    }
    if (selectedColor_ >= 0 && selectedColor_ < static_cast<int>(changed.color.size())) {
        auto& p = changed.color[static_cast<std::size_t>(selectedColor_)];
        float rgb[3] = {static_cast<float>(p.rgb.r), static_cast<float>(p.rgb.g), static_cast<float>(p.rgb.b)};
        ImGui::Text("colour point %d at %.4g", selectedColor_, p.value);
        bool picked = ImGui::ColorEdit3("colour", rgb);
        tooltip("the colour the transfer function gives at this value (colours between points are blended)");
        if (picked) {
            p.rgb = glm::clamp(glm::dvec3(rgb[0], rgb[1], rgb[2]), 0.0, 1.0);
            dirty = true;
        }
    }
    ImGui::TextDisabled("drag: move  double-click: add  right-click: remove  (values %.4g .. %.4g)", lo, hi);

    // The gradient-opacity curve: the opacity factor over |gradient| (value units per mm) from 0 to the
    // volume's largest (or the last point, when beyond). Off: no points (a factor of 1 everywhere); turned on,
    // a flat 1 to shape from.
    bool gradientOn = !changed.gradientOpacity.empty();
    const double gradientHi = std::max({maxGradient_, gradientOn ? changed.gradientOpacity.back().value : 0.0, 1e-6});
    bool gradientClicked = ImGui::Checkbox("gradient opacity", &gradientOn);
    tooltip("scale the opacity by how sharply the value changes: shows boundaries, hides flat regions");
    if (gradientClicked) {
        changed.gradientOpacity.clear();
        if (gradientOn) changed.gradientOpacity = {{0.0, 1.0}, {gradientHi, 1.0}};
        draggedGradient_ = -1;
        dirty = true;
    }
    if (!changed.gradientOpacity.empty()) {
        ImVec2 g = ImGui::GetCursorScreenPos();
        gradientCanvas_ = {g.x, g.y, width, gradientHeight, 0.0, gradientHi};
        draw->AddRectFilled(g, ImVec2(g.x + width, g.y + gradientHeight), IM_COL32(30, 30, 34, 255));
        dirty |= editPointCurve("gradient opacity curve", gradientCanvas_, changed.gradientOpacity, draggedGradient_,
                                [](double) { return IM_COL32(200, 200, 210, 255); });
        ImGui::TextDisabled("|gradient| 0 .. %.4g per mm (the volume's largest: %.4g)", gradientHi, maxGradient_);
    }
    if (dirty) edits.push_back(edit(Setting::TransferFunction, tfJson(changed)));

    // Presets, load and save (JSON or .vp by the extension).
    std::string current = tf.name.empty() ? "(preset)" : tf.name;
    if (ImGui::BeginCombo("preset", current.c_str())) {
        for (const std::filesystem::path& p : presets_)
            if (ImGui::Selectable(p.filename().c_str())) {
                try {
                    edits.push_back(edit(Setting::TransferFunction, tfJson(io::readTransferFunction(p))));
                } catch (const std::exception& e) {
                    messages_.push_back(e.what());
                }
            }
        ImGui::EndCombo();
    }
    tooltip("a shipped transfer function (assets/tf): CT bone, soft tissue, MRI ...");
    ImGui::InputText("TF file", tfPath_, sizeof tfPath_);
    tooltip("a transfer function file: curette JSON or 3D Slicer .vp (by its extension)");
    bool load = ImGui::Button("load TF");
    tooltip("replace the transfer function by the file's");
    if (load) {
        try {
            edits.push_back(edit(Setting::TransferFunction, tfJson(io::readTransferFunction(tfPath_))));
            messages_.push_back(std::string("loaded ") + tfPath_);
        } catch (const std::exception& e) {
            messages_.push_back(e.what());
        }
    }
    ImGui::SameLine();
    bool save = ImGui::Button("save TF (.json or .vp)");
    tooltip("write the transfer function on screen to the file named above");
    if (save) {
        try {
            io::writeTransferFunction(tfPath_, tf);
            messages_.push_back("wrote the transfer function to " + std::filesystem::absolute(tfPath_).string());
        } catch (const std::exception& e) {
            messages_.push_back(e.what());
        }
    }
}

void ViewPanels::shadingPanel(const InteractionState& state, std::vector<SettingEdit>& edits) {
    const Scene& scene = loaded_.scene;
    int mode = static_cast<int>(state.shading);
    std::string modes;
    for (int m = 0; m < static_cast<int>(ShadingMode::Count); ++m) modes += std::string(shadingModeName(static_cast<ShadingMode>(m))) + '\0';
    if (ImGui::Combo("shading", &mode, modes.c_str())) edits.push_back(edit(Setting::Shading, shadingModeName(static_cast<ShadingMode>(mode))));
    tooltip("how the volume is lit: solid (no light), phong, lao / cao (ambient occlusion, exact under the carve), dos (directional occlusion), ismos (multidirectional)");

    if (usesAmbientOcclusion(state.shading)) {
        nlohmann::json ao = objectOf(state, scene, "ambient_occlusion");
        bool changed = false;
        static const char* const kRays[] = {"6", "14", "26", "54"};
        std::string rays = ao.contains("rays") ? (ao["rays"].is_string() ? ao["rays"].get<std::string>() : ao["rays"].dump()) : "26";
        if (ImGui::BeginCombo("AO rays", rays.c_str())) {
            for (const char* r : kRays)
                if (ImGui::Selectable(r, rays == r)) ao["rays"] = r, changed = true;
            ImGui::EndCombo();
        }
        int samples = state.lao.samples;
        tooltip("directions each voxel's ambient occlusion looks along");
        if (ImGui::SliderInt("AO samples", &samples, 1, 64)) ao["samples"] = samples, changed = true;
        tooltip("samples along each direction");
        float step = static_cast<float>(state.lao.stepMm);
        if (ImGui::SliderFloat("AO step (mm)", &step, 0.25f, 4.0f)) ao["step_mm"] = step, changed = true;
        tooltip("distance between samples: samples x step is how far occlusion reaches");
        float scale = static_cast<float>(state.lao.ambientScale);
        if (ImGui::SliderFloat("ambient scale", &scale, 0.0f, 4.0f)) ao["ambient_scale"] = scale, changed = true;
        tooltip("how strongly occlusion darkens");
        if (changed) edits.push_back(edit(Setting::AmbientOcclusion, ao));
    }
    if (slabPassRuns(state.shading, !state.tubes.empty())) {
        nlohmann::json dos = objectOf(state, scene, "dos");
        bool changed = false;
        float cone = static_cast<float>(state.dos.coneAngleDeg);
        if (ImGui::SliderFloat("shadow cone (deg)", &cone, 5.0f, 85.0f)) dos["cone_angle_deg"] = cone, changed = true;
        tooltip("opening angle of the light cone the directional occlusion gathers over");
        int grid = state.dos.gridSize;
        if (ImGui::SliderInt("shadow grid", &grid, 1, 8)) dos["grid"] = grid, changed = true;
        tooltip("samples across the cone per side: more is smoother and slower");
        if (changed) edits.push_back(edit(Setting::Dos, dos));
    }
    if (state.shading == ShadingMode::Ismos) {
        nlohmann::json ismos = objectOf(state, scene, "ismos");
        bool changed = false;
        bool partial = state.ismos.partial;
        if (ImGui::Checkbox("partial occlusion", &partial)) ismos["occlusion"] = partial ? "partial" : "full", changed = true;
        tooltip("occlusion from the layers in front only (partial) or all (full)");
        int samples = state.ismos.lightSamples;
        if (ImGui::SliderInt("light samples", &samples, 1, 64)) ismos["light_samples"] = samples, changed = true;
        tooltip("directions sampled over each light");
        int points = state.ismos.testPoints;
        if (ImGui::SliderInt("test points", &points, 1, 128)) ismos["test_points"] = points, changed = true;
        tooltip("points tested for occlusion per pixel");
        int layers = state.ismos.layers;
        if (ImGui::SliderInt("layers", &layers, 1, 4)) ismos["layers"] = layers, changed = true;
        tooltip("depth layers the image is split into");
        float ambient = static_cast<float>(state.ismos.ambient);
        if (ImGui::SliderFloat("ambient", &ambient, 0.0f, 1.0f)) ismos["ambient"] = ambient, changed = true;
        tooltip("light that reaches everywhere");
        if (changed) edits.push_back(edit(Setting::Ismos, ismos));
    }
    nlohmann::json rc = objectOf(state, scene, "raycast");
    bool changed = false;
    float step = static_cast<float>(state.raycast.stepMm);
    if (ImGui::SliderFloat("ray step (mm)", &step, 0.0f, 2.0f, step > 0 ? "%.2f" : "auto")) rc["step_mm"] = step, changed = true;
    tooltip("distance between samples along each view ray; 0: automatic, from the voxel size");
    bool faces = state.raycast.cutFace.enabled;
    bool facesClicked = ImGui::Checkbox("cut faces", &faces);
    tooltip("shade the surfaces the carve cuts like the tissue behind them");
    if (facesClicked) {
        nlohmann::json f = rc.contains("cut_faces") && rc["cut_faces"].is_object() ? rc["cut_faces"] : nlohmann::json::object();
        f["enabled"] = faces;
        rc["cut_faces"] = f;
        changed = true;
    }
    if (changed) edits.push_back(edit(Setting::Raycast, rc));
}

void ViewPanels::meshPanel(const InteractionState& state, const OrbitCamera& camera, const input::InputPipeline& input,
                           std::vector<SettingEdit>& edits) {
    // Who holds which mesh: the keyboard and every binding whose device is connected, each with the mesh index
    // it moves (the mapper's and the keyboard's own state).
    struct Holder {
        int binding;
        std::string name;
        int mesh;
    };
    std::vector<Holder> holders{{input::kKeyboardBinding, "keyboard", input.keyboardSelection()}};
    const input::Mapper& mapper = input.mapper();
    for (std::size_t b = 0; b < mapper.config().bindings.size(); ++b) {
        int binding = static_cast<int>(b), device = mapper.boundDevice(binding);
        if (device < 0) continue;
        const input::DeviceBinding& config = mapper.config().bindings[b];
        holders.push_back({binding, config.family + " #" + std::to_string(config.index) + " (device " + std::to_string(device) + ")",
                           mapper.heldMesh(binding)});
    }
    const int meshCount = static_cast<int>(state.meshes.size());
    auto meshLabel = [&](int index) {
        return index >= 0 && index < meshCount ? state.meshes[static_cast<std::size_t>(index)].name + " (id " + std::to_string(state.meshes[static_cast<std::size_t>(index)].id) + ")"
                                               : std::string("no mesh");
    };
    ImGui::PushID("holders");   // apart from the meshes' ids below
    for (const Holder& h : holders) {
        ImGui::PushID(h.binding);
        if (ImGui::BeginCombo(h.name.c_str(), meshLabel(std::min(h.mesh, meshCount - 1)).c_str())) {
            for (int i = 0; i < meshCount; ++i)
                if (ImGui::Selectable(meshLabel(i).c_str(), i == h.mesh) && i != h.mesh) holdRequests_.push_back({h.binding, i});
            ImGui::EndCombo();
        }
        ImGui::PopID();
    }
    ImGui::PopID();
    // The meshes drawn over the image (render/clip_mesh_overlay.h): shown in the viewer unless the scene or an
    // edit says otherwise; an edit of the scene's "clip_mesh_display", so a session records it.
    bool show = state.clipMeshDisplay.show.value_or(true);
    if (ImGui::Checkbox("show tools", &show)) {
        nlohmann::json display = objectOf(state, loaded_.scene, "clip_mesh_display");
        display["show"] = show;
        edits.push_back(edit(Setting::ClipMeshDisplay, display));
    }
    tooltip("draw the clip meshes over the image: each in its own colour, outlined, the held one highlighted");
    for (std::size_t index = 0; index < state.meshes.size(); ++index) {
        const MeshState& m = state.meshes[index];
        ImGui::PushID(m.id);
        std::string heldBy;
        for (const Holder& h : holders)
            if (std::min(h.mesh, meshCount - 1) == static_cast<int>(index)) heldBy += (heldBy.empty() ? "" : ", ") + h.name;
        ImGui::Text("%s (id %d)%s%s", m.name.c_str(), m.id, heldBy.empty() ? "" : ", held by ", heldBy.c_str());
        float scale = static_cast<float>(m.scale.x);
        if (ImGui::SliderFloat("scale (x its size)", &scale, 0.1f, 5.0f, "%.3f", ImGuiSliderFlags_Logarithmic))
            edits.push_back(edit(Setting::MeshScale, scale, m.id));
        tooltip("grows or shrinks the mesh about its origin; its shape's sizes are in its description");
        // Position and rotation in RAS mm and degrees, as a scene file gives them: typed or dragged, an edit.
        float position[3] = {static_cast<float>(m.pose.position.x), static_cast<float>(m.pose.position.y), static_cast<float>(m.pose.position.z)};
        glm::dvec3 degrees = clip::degreesFromOrientation(m.pose.orientation);
        float rotation[3] = {static_cast<float>(degrees.x), static_cast<float>(degrees.y), static_cast<float>(degrees.z)};
        bool moved = ImGui::DragFloat3("position (RAS mm)", position, 0.1f, -1e4f, 1e4f, "%.1f");
        tooltip("the mesh origin in scanner coordinates: R(ight), A(nterior), S(uperior), mm; drag or Ctrl+click to type");
        bool turned = ImGui::DragFloat3("rotation (deg)", rotation, 0.5f, -360.0f, 360.0f, "%.1f");
        tooltip("degrees about the R, A and S axes, applied in that order");
        if (moved || turned)
            edits.push_back(edit(Setting::MeshPose, {{"position_mm", {position[0], position[1], position[2]}},
                                                     {"rotation_deg", {rotation[0], rotation[1], rotation[2]}}}, m.id));
        bool clips = m.clipsTubes;
        if (ImGui::Checkbox("clips tubes", &clips)) edits.push_back(edit(Setting::MeshClipsTubes, clips, m.id));
        tooltip("the mesh also cuts the fibre tubes it passes through");
        ImGui::SameLine();
        if (ImGui::Button("shape...")) ImGui::OpenPopup("shape");
        if (ImGui::BeginPopup("shape")) {
            for (const char* shape : kPrimitiveShapes)
                if (ImGui::Selectable(shape)) edits.push_back(edit(Setting::MeshShape, primitiveMeshJson(shape, addSizeMm_), m.id));
            ImGui::EndPopup();
        }
        ImGui::SameLine();
        if (ImGui::Button("remove")) edits.push_back(edit(Setting::MeshRemove, nullptr, m.id));
        tooltip("removes this mesh (Delete removes the held one)");
        ImGui::PopID();
    }
    ImGui::Combo("new shape", &addShape_, kPrimitiveShapes, 6);
    tooltip("the shape of a mesh added below (or given to a mesh by its shape... button)");
    ImGui::SliderFloat(primitiveSizeName(kPrimitiveShapes[addShape_]), &addSizeMm_, 1.0f, 60.0f, "%.1f");
    tooltip("the new shape's main size; the others follow from it (see the label)");
    bool add = ImGui::Button("add mesh at the view's centre");
    tooltip("adds the shape at the point the camera turns around (Home: the volume's centre)");
    if (add && static_cast<int>(state.meshes.size()) < clip::kMaxClipMeshes) {
        nlohmann::json entry = {{"mesh", primitiveMeshJson(kPrimitiveShapes[addShape_], addSizeMm_)},
                                {"position_mm", {camera.target.x, camera.target.y, camera.target.z}}};
        edits.push_back(edit(Setting::MeshAdd, entry));
    }
}

void ViewPanels::tubePanel(const InteractionState& state, std::vector<SettingEdit>& edits) {
    const Scene& scene = loaded_.scene;
    bool lines = state.tubeRendering.lines;
    bool linesClicked = ImGui::Checkbox("illuminated lines", &lines);
    tooltip("draw the tracts as lit lines instead of tubes (cheaper for many streamlines)");
    if (linesClicked) {
        nlohmann::json r = objectOf(state, scene, "tube_rendering");
        r["mode"] = lines ? "lines" : "tubes";
        edits.push_back(edit(Setting::TubeRendering, r));
    }
    for (std::size_t i = 0; i < state.tubes.size(); ++i) {
        const SceneTubes& t = state.tubes[i];
        ImGui::PushID(static_cast<int>(i));
        nlohmann::json entry = objectOf(state, scene, "tubes[" + std::to_string(i) + "]");
        entry.erase("path");
        bool changed = false;
        ImGui::Text("%s", t.name.c_str());
        float radius = static_cast<float>(t.settings.radiusMm);
        if (ImGui::SliderFloat("tube radius (mm)", &radius, 0.05f, 3.0f)) entry["radius_mm"] = radius, changed = true;
        tooltip("radius of each streamline's tube");
        int coloring = t.settings.coloring == TubeSettings::Coloring::Uniform ? 1 : t.settings.coloring == TubeSettings::Coloring::Scalar ? 2 : 0;
        const char* modes = t.settings.scalarName.empty() ? "direction\0uniform\0" : "direction\0uniform\0scalar\0";
        if (ImGui::Combo("colour", &coloring, modes)) {
            if (coloring == 1) entry["color"] = {t.settings.uniformColor.r, t.settings.uniformColor.g, t.settings.uniformColor.b};
            else entry["color"] = coloring == 2 ? "scalar" : "direction";
            changed = true;
        }
        if (t.settings.coloring == TubeSettings::Coloring::Uniform) {
            float rgb[3] = {static_cast<float>(t.settings.uniformColor.r), static_cast<float>(t.settings.uniformColor.g), static_cast<float>(t.settings.uniformColor.b)};
            if (ImGui::ColorEdit3("tube colour", rgb)) entry["color"] = {rgb[0], rgb[1], rgb[2]}, changed = true;
        }
        if (changed) edits.push_back(edit(Setting::Tubes, entry, static_cast<int>(i)));
        ImGui::PopID();
    }
}

void ViewPanels::lightPanel(const InteractionState& state, std::vector<SettingEdit>& edits) {
    // Apart from the meshes' and the bundles' widgets, which are numbered too (mesh 1's "remove" is not light
    // 1's).
    ImGui::PushID("lights");
    for (std::size_t i = 0; i < state.lights.size(); ++i) {
        const Light& l = state.lights[i];
        ImGui::PushID(static_cast<int>(i));
        nlohmann::json entry = objectOf(state, loaded_.scene, "lights[" + std::to_string(i) + "]");
        bool changed = false;
        ImGui::Text("light %zu (%s space)%s", i, l.cameraSpace ? "camera" : "world", static_cast<int>(i) == state.selectedLight ? " (selected)" : "");
        if (state.lights.size() > 1) {   // one light always stays
            ImGui::SameLine();
            if (ImGui::Button("remove")) edits.push_back(edit(Setting::LightRemove, nullptr, static_cast<int>(i)));
        }
        float d[3] = {static_cast<float>(l.direction.x), static_cast<float>(l.direction.y), static_cast<float>(l.direction.z)};
        if (ImGui::DragFloat3("direction", d, 0.01f, -1.0f, 1.0f) && std::abs(d[0]) + std::abs(d[1]) + std::abs(d[2]) > 1e-3f)
            changed = true;
        entry["direction"] = changed ? nlohmann::json{d[0], d[1], d[2]} : nlohmann::json{l.direction.x, l.direction.y, l.direction.z};
        glm::dvec3 rgb = entry.contains("color") ? glm::dvec3(entry["color"][0].get<double>(), entry["color"][1].get<double>(), entry["color"][2].get<double>())
                                                 : glm::dvec3(1.0);
        float c[3] = {static_cast<float>(rgb.r), static_cast<float>(rgb.g), static_cast<float>(rgb.b)};
        if (ImGui::ColorEdit3("colour", c)) entry["color"] = {c[0], c[1], c[2]}, changed = true;
        float intensity = entry.contains("intensity") ? entry["intensity"].get<float>() : 1.0f;
        if (ImGui::SliderFloat("intensity", &intensity, 0.0f, 4.0f)) entry["intensity"] = intensity, changed = true;
        if (changed) edits.push_back(edit(Setting::Light, entry, static_cast<int>(i)));
        ImGui::PopID();
    }
    // A new light, camera space, from the upper left (the scene's default comes from the upper right).
    if (state.lights.size() < kMaxSceneLights && ImGui::Button("add light"))
        edits.push_back(edit(Setting::LightAdd, {{"direction", {-0.5, 0.5, 1.0}}, {"space", "camera"}}));
    ImGui::PopID();
}

void ViewPanels::scenePanel(const InteractionState& state, const OrbitCamera& camera) {
    ImGui::InputText("scene file", scenePath_, sizeof scenePath_);
    bool save = ImGui::Button("save scene");
    tooltip("writes the scene with its current meshes, poses, settings and camera");
    if (save) {
        try {
            saveScene(scenePath_, loaded_.scene, loaded_.scene.json.dump(), state, &camera);
            bool drilled = state.removal && !state.removal->empty();
            messages_.push_back("wrote the scene to " + std::filesystem::absolute(scenePath_).string() +
                                (drilled ? " and its removal to " + removalFileBeside(scenePath_).filename().string() : ""));
        } catch (const std::exception& e) {
            messages_.push_back(std::string("could not write the scene: ") + e.what());
        }
    }
}

}  // namespace curette
