#include "viewer/view_sidebar.h"

#include "viewer/orientation_marker.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace curette {

namespace {

const ImVec4 kRed(1, 0.35f, 0.35f, 1), kGrey(0.85f, 0.85f, 0.85f, 1);

std::string mm(double v) {
    if (!std::isfinite(v)) return "-";
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", v);
    return text;
}

// Every key of the viewer and what it does, in one place.
struct KeyHelp {
    const char* keys;
    const char* what;
};
const KeyHelp kKeys[] = {
    {"left drag / wheel", "turn the view around the volume / zoom"},
    {"Home", "reset the view; A P L R S I buttons (View tab): standard views"},
    {"W A S D Q E", "move the held clip mesh (camera frame: forward, left, back, right, down, up)"},
    {"arrows, PgUp/PgDn", "turn the held mesh (pitch, yaw, roll)"},
    {"right drag", "move the held mesh in the view plane"},
    {"Shift (held)", "fine steps: a tenth of the speed for keys and devices"},
    {"Tab / R", "hold the next mesh / put it back where the scene had it"},
    {"Insert / Delete", "add a mesh / remove the held one"},
    {"B / N (hold)", "drill / erase with the held mesh: it removes what it sweeps (SpaceMouse: hold the right button; gamepad: R2 / L2)"},
    {"Ctrl+Z / Ctrl+Shift+Z or Ctrl+Y", "undo / redo a drill stroke or a panel edit (a gamepad: D-pad left / right)"},
    {"1 2 3 4 5 6, C", "shading: solid, phong, lao, cao, dos, ismos; C cycles"},
    {"O; I J K L; Shift + left drag", "next light; turn it"},
    {"Ctrl + left click", "put the slices' crosshair on the first visible surface under the cursor (and a ruler point when measuring)"},
    {"M; Esc", "measure: a ruler between two points clicked in the view or on a slice; Esc clears it"},
    {"wheel / click on a slice", "scroll the slice / move the crosshair there (Slices tab)"},
    {"F1, H, ?", "this help"},
    {"F2", "fold the side bar away (the view takes the window)"},
    {"F3", "stereo: off, side by side, anaglyph"},
    {"F5", "write the plan (report and exports) into a new folder"},
    {"F9", "start / stop recording a session"},
    {"P, F12", "screenshot of the 3-D view"},
    {"SpaceMouse / gamepad", "moves the mesh it holds (device panel in Settings); its buttons as mapped"},
};

}  // namespace

void tooltip(const char* text) {
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

void note(const char* text) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
    ImGui::TextWrapped("%s", text);
    ImGui::PopStyleColor();
}

void drawPlanTable(const plan::Report& r, bool current) {
    ImGui::Text("removed %.2f +-%.2f mL%s", r.removedMl, r.removedUncertaintyMl, current ? "" : " (updating)");
    tooltip("tissue the clip meshes remove, from sub-voxel coverage; +- the partly covered voxels' share");
    const bool anyStructure = std::any_of(r.structures.begin(), r.structures.end(), [](const plan::StructureRow& row) { return row.touched || row.isProtected; });
    if (!anyStructure && r.bundles.empty()) return;   // no labels and no tracts: the volume alone says it
    const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp | ImGuiTableFlags_BordersInnerH;
    if (!ImGui::BeginTable("plan", 3, flags)) return;
    ImGui::TableSetupColumn("structure", ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableSetupColumn("mL", ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableSetupColumn("mm", ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableHeadersRow();
    for (const plan::StructureRow& row : r.structures) {
        if (!row.touched && !row.isProtected) continue;
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextColored(row.isProtected && row.touched ? kRed : kGrey, "%s%s", row.isProtected ? "! " : "", row.name.c_str());
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("%s%s\nremoved %.3f +-%.3f mL (%.1f %% of %.2f mL)\n%s %.1f +-%.2f mm", row.name.c_str(),
                              row.isProtected ? " (protected)" : "", row.removedMl, row.removedUncertaintyMl, 100 * row.share, row.volumeMl,
                              row.touched ? "carved to a depth of" : "margin to the carve", row.touched ? row.intrusionDepthMm : row.marginMm,
                              row.touched ? row.intrusionUncertaintyMm : row.marginUncertaintyMm);
        ImGui::TableNextColumn();
        ImGui::Text("%.2f", row.removedMl);
        ImGui::TableNextColumn();
        ImGui::Text("%s%s", row.touched ? "in " : "", mm(row.touched ? row.intrusionDepthMm : row.marginMm).c_str());
    }
    for (const plan::BundleRow& b : r.bundles) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextColored(b.isProtected && b.cut ? kRed : kGrey, "%s%s", b.isProtected ? "! " : "", b.name.c_str());
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("bundle %s%s\n%llu of %llu streamlines cut, %.1f mm of fibre removed\nmargin %.1f +-%.1f mm", b.name.c_str(),
                              b.isProtected ? " (protected)" : "", static_cast<unsigned long long>(b.cut),
                              static_cast<unsigned long long>(b.streamlines), b.removedLengthMm, b.marginMm, b.marginUncertaintyMm);
        ImGui::TableNextColumn();
        ImGui::Text("%llu cut", static_cast<unsigned long long>(b.cut));
        ImGui::TableNextColumn();
        ImGui::Text("%s", mm(b.marginMm).c_str());
    }
    ImGui::EndTable();
    ImGui::PushStyleColor(ImGuiCol_Text, kRed);
    for (const std::string& warning : r.warnings()) ImGui::TextWrapped("%s", warning.c_str());
    ImGui::PopStyleColor();
    note("mm: margin, or 'in' depth");
    tooltip("mm: the distance from the carve to the structure; 'in': how deep the carve reaches into it");
}

void drawTractLegend(const InteractionState& state) {
    if (state.tubes.empty()) return;
    bool direction = false;
    for (const SceneTubes& t : state.tubes) {
        if (t.settings.coloring == TubeSettings::Coloring::Uniform) {
            glm::dvec3 c = t.settings.uniformColor;
            ImGui::ColorButton(t.name.c_str(), ImVec4(static_cast<float>(c.r), static_cast<float>(c.g), static_cast<float>(c.b), 1),
                               ImGuiColorEditFlags_NoTooltip, ImVec2(12, 12));
            ImGui::SameLine();
            ImGui::Text("%s%s", t.name.c_str(), t.protectedBundle ? " (protected)" : "");
        } else {
            ImGui::Bullet();
            ImGui::TextWrapped("%s: %s%s", t.name.c_str(), t.settings.coloring == TubeSettings::Coloring::Scalar ? "by its scalar" : "by direction",
                               t.protectedBundle ? " (protected)" : "");
            direction |= t.settings.coloring == TubeSettings::Coloring::Direction;
        }
    }
    if (direction) note("direction: red left-right, green front-back, blue up-down");
}

void drawHelpWindow(bool* open, ViewRect view) {
    if (!*open) return;
    // Within the 3-D view whatever its size: a fixed width, the descriptions wrapped.
    const float width = std::min(720.0f, static_cast<float>(view.size.x) - 24.0f);
    ImGui::SetNextWindowPos(ImVec2(view.origin.x + 0.5f * view.size.x, view.origin.y + 0.5f * view.size.y), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowSizeConstraints(ImVec2(width, 0), ImVec2(width, static_cast<float>(view.size.y) - 24.0f));
    if (ImGui::Begin("help (F1, H, ? or Esc closes)", open, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse)) {
        if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg)) {
            ImGui::TableSetupColumn("keys", ImGuiTableColumnFlags_WidthFixed, 0.32f * width);
            ImGui::TableSetupColumn("what", ImGuiTableColumnFlags_WidthStretch);
            for (const KeyHelp& k : kKeys) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::TextWrapped("%s", k.keys);
                ImGui::TableNextColumn();
                ImGui::TextWrapped("%s", k.what);
            }
            ImGui::EndTable();
        }
        note("PREVIEW: a quick image while something moves; FULL QUALITY: the exact image, once still.");
    }
    ImGui::End();
}

ViewRect drawOrientationMarker(const OrbitCamera& camera, ViewRect view) {
    const float radius = 34, margin = 12;
    const ImVec2 centre(static_cast<float>(view.origin.x) + margin + radius, static_cast<float>(view.origin.y + view.size.y) - margin - radius);
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    for (const MarkerAxis& a : orientationMarker(camera)) {
        ImVec2 end(centre.x + radius * 0.75f * static_cast<float>(a.screen.x), centre.y + radius * 0.75f * static_cast<float>(a.screen.y));
        glm::dvec3 c = glm::abs(a.direction);   // R/L red, A/P green, S/I blue, as the tract colours
        ImU32 colour = IM_COL32(static_cast<int>(80 + 175 * c.x), static_cast<int>(80 + 175 * c.y), static_cast<int>(80 + 175 * c.z), 255);
        draw->AddLine(centre, end, colour, a.depth >= 0 ? 2.5f : 1.5f);
        const char label[2] = {a.label, 0};
        ImVec2 text(centre.x + radius * 0.95f * static_cast<float>(a.screen.x) - 4, centre.y + radius * 0.95f * static_cast<float>(a.screen.y) - 7);
        draw->AddText(text, a.depth >= 0 ? IM_COL32(255, 255, 255, 255) : IM_COL32(160, 160, 160, 255), label);
    }
    const int side = static_cast<int>(2 * (radius + margin));
    return {{view.origin.x, view.origin.y + view.size.y - side}, {side, side}};
}

}  // namespace curette
