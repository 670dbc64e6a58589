#pragma once
// Shading modes (mirrored by shaders/shading_modes.glsl) and what each needs, in one table
// (render/model/shading_mode.cpp): the frame plan, the viewer's shading cycle and the scene reader all read it, so a
// new mode is one enum value, one table row and its colour in shaders/shade_sample.glsl. A mode allocates
// only what it uses.

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace curette {

enum class ShadingMode { Solid = 0, Phong = 1, Lao = 2, Cao = 3, Dos = 4, Ismos = 5, Count };

struct ShadingModeTraits {
    ShadingMode mode;
    const char* name;
    bool ambientOcclusion;    // needs V_o, V_PAO, V_AO (steps I, IV, V)
    bool dilatedMaps;         // step IV tests the dilated maps (cao); lao recomputes every visible voxel
    bool slabPass;            // the volume is integrated slice by slice even without tubes (dos)
    bool tubesInSlabPass;     // tubes go through the slab pass (seed 000's combined occlusion and the vicinity
                              // term); the other modes but ismos shade them in the ray cast (tube_surface.glsl)
    const char* description;
};

const ShadingModeTraits& traits(ShadingMode mode);
std::span<const ShadingModeTraits> allShadingModes();
const char* shadingModeName(ShadingMode mode);
std::optional<ShadingMode> parseShadingMode(std::string_view name);
// "solid, phong, ..." for messages.
std::string shadingModeList();
// The mode after `mode` in the table's order (the viewer's "next shading").
ShadingMode nextShadingMode(ShadingMode mode);
// Modes that need ambient occlusion volumes (V_o, V_PAO, V_AO).
inline bool usesAmbientOcclusion(ShadingMode m) { return traits(m).ambientOcclusion; }

}  // namespace curette
