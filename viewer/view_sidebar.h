#pragma once
// What the viewer shows besides the volume, in planner's words (Dear ImGui, no GL call): the compact plan table
// with details on demand, the tract legend, the help window (F1, H, ?) with every key and device control, and the
// orientation marker in a corner of the 3-D view. tools/commands/view.cpp places them in the side bar
// (viewer/view_layout.h).

#include "plan/removal_report.h"
#include "session/interaction.h"
#include "viewer/view_layout.h"

namespace curette {

// The removal report as a table: one row per structure the carve touches or must spare and per bundle, the
// protected ones in red when reached; hover a row for its uncertainties, voxels and share.
void drawPlanTable(const plan::Report& report, bool current);

// Which tube colour is which bundle (uniform colours as a swatch; direction colouring's axis colours).
void drawTractLegend(const InteractionState& state);

// The keys and device controls, one list (the help window and the README's table are from the same words).
void drawHelpWindow(bool* open, ViewRect view);

// The patient axes (viewer/orientation_marker.h) in the bottom-left corner of `view`; returns where it drew.
ViewRect drawOrientationMarker(const OrbitCamera& camera, ViewRect view);

// A tooltip for the last widget (every panel control has one).
void tooltip(const char* text);
// A note in the disabled colour, wrapped at the side bar's width.
void note(const char* text);

}  // namespace curette
