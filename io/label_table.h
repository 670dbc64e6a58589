#pragma once
// Label tables: the names and colours of the ids of a label volume (base/label_map.h). The formats, and the
// sources their rules follow (Slicer: vtkMRMLColorTableStorageNode.cxx; MRIcron:
// nifti_img.pas LoadColorScheme; mricron-data 1.2.20211006 templates):
//
//  MricronNames  `index name [code]` per line, CRLF or LF, e.g. mricron's aal.nii.txt (`1 Precentral_L 2001`)
//                and the JHU form `index<TAB>name`. With a tab after the index the name is the rest of the line
//                (trimmed). Otherwise MRIcron keeps all text after the index as the name, except for atlas
//                codes: the last word is read as a code column (AAL's 2001, AICHA's 2) and left out of the name
//                when, on EVERY data line of the file, at least two words follow the index and the last one
//                is an integer. So a table in which only some names end in a number keeps those numbers in
//                the names. Codes are not kept. readLabelTable colours the entries from the sibling LUT
//                (`X.nii.txt` -> `X.nii.lut`) when it exists: 768 bytes, PLANAR (256 R, then 256 G, then
//                256 B), entry i is the colour of label i, label 0 transparent (MRIcron's invisible colour).
//  ColorTable    `index name r g b [a]`, one word for the name, colours 0..255 (a missing alpha is 255).
//  SlicerTable   3D Slicer `.ctbl` (or `.txt`): `#` comments, `index name r g b a`, values clamped to 0..255
//                then / 255, every `_` in a name read as a space, a missing alpha read as 0 (Slicer's code).
//  SlicerCsv     Slicer's CSV form: a header line naming the columns LabelValue, Name, Color_R, Color_G,
//                Color_B and optionally Color_A (any order, other columns ignored), then one row per label;
//                fields may be double-quoted; colours clamped to 0..255, a missing Color_A column is 255;
//                names are kept as written.
//
// Detection (detectLabelTableFormat), in this order: a first data line whose first comma-separated field is
// `LabelValue` -> SlicerCsv; a `# Color procedural file` line -> refused (a procedural colour file is a
// function, not a table); a `.ctbl` extension or a `# Color table file` comment -> SlicerTable; every data
// line having 5 or 6 words, the first and the last 3 or 4 integers, the colour ones in 0..255 -> ColorTable;
// anything else -> MricronNames. Blank lines are skipped in every format, `#` lines in all but SlicerCsv's
// data. Ids are integers 0..65535, each at most once. Errors name the file and "line N".
//
// Labels a table does not colour (a names-only file without LUT, ids above 255 of a LUT) get the generated
// colour of their id; ids a table lacks get the generated entry "label N" (generatedLabel).

#include "base/label_map.h"

#include <filesystem>
#include <string>
#include <string_view>

namespace curette::io {

enum class LabelTableFormat { MricronNames, ColorTable, SlicerTable, SlicerCsv };

// Reads a label table by the rules above; a MricronNames file takes its colours from the sibling .lut.
LabelTable readLabelTable(const std::filesystem::path& path);
// The same from text (no LUT lookup: names-only entries get generated colours). `source` names the text in
// messages and its extension counts for the detection (".ctbl").
LabelTable readLabelTableText(std::string_view text, const std::string& source);
LabelTableFormat detectLabelTableFormat(std::string_view text, const std::string& source);

// A bare mricron/ImageJ .lut (768 bytes, planar): entries 0..255 named "label N", entry 0 transparent.
LabelTable readLut(const std::filesystem::path& path);

// The deterministic stand-in for a label without a colour: hues spread by the golden angle, so neighbouring
// ids differ; id 0 is transparent black.
glm::dvec4 generatedLabelColor(int id);
// {id, "label N", generatedLabelColor(id)}.
LabelEntry generatedLabel(int id);
// The table's entry for `id`, or generatedLabel(id) when it has none.
LabelEntry labelEntryFor(const LabelTable& table, int id);
// Adds generatedLabel(id) for every non-zero id of `map` that `table` lacks (in increasing id order).
void addMissingLabels(LabelTable& table, const LabelMap& map);

}  // namespace curette::io
