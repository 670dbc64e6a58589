#pragma once
// Transfer-function files: curette's JSON and 3D Slicer's volume-property text (.vp).
//
// JSON (assets/tf/README.md):
//   {"name": "MRI T1", "unit_length_mm": 1.0,
//    "color": [[value, r, g, b], ...],            r, g, b in [0, 1], values increasing
//    "opacity": [[value, alpha], ...],            alpha of a unit_length_mm slab, in [0, 1]
//    "gradient_opacity": [[|gradient|, factor], ...]   optional, |gradient| in value units per mm
//    "material": {"ambient": .2, "diffuse": .8, "specular": .3, "specular_power": 20}}   optional
//
// Slicer .vp: nine lines: interpolation, shade, diffuse, ambient, specular, specular power, then the scalar
// opacity and gradient opacity as "N x0 y0 x1 y1 ..." (N numbers follow) and the colour as
// "N x0 r0 g0 b0 ..." (vtkMRMLVolumePropertyStorageNode).

#include "base/transfer_function.h"

#include <nlohmann/json_fwd.hpp>

#include <filesystem>
#include <string>
#include <string_view>

namespace curette {
class JsonReader;
}

namespace curette::io {

TransferFunction readTransferFunction(const std::filesystem::path& path);
// `keyPrefix` names where an inline TF sits in a scene (e.g. "transfer_function"), so errors carry full keys.
TransferFunction parseTransferFunctionJson(const nlohmann::json& json, const std::string& source, const std::string& keyPrefix = "");
TransferFunction parseTransferFunctionJsonText(std::string_view text, const std::string& source);
TransferFunction parseSlicerVolumeProperty(std::string_view text, const std::string& source);
std::string writeTransferFunctionJson(const TransferFunction& tf);
// The same TF as a 3D Slicer volume property (.vp): linear interpolation, shading on, the material, then the
// three functions. A .vp has no name and no unit length: it reads back with the file's stem as its name and a
// unit length of 1 mm (the .vp convention), every point and the material exactly (17 significant digits).
std::string writeSlicerVolumeProperty(const TransferFunction& tf);
// Writes `tf` atomically as JSON or .vp by the extension of `path` (InputError for any other).
void writeTransferFunction(const std::filesystem::path& path, const TransferFunction& tf);
// The "material" object of a TF file or a scene's tubes: keys it names override `material`'s fields.
void readMaterial(const JsonReader& object, TransferFunction::Material& material);

}  // namespace curette::io
