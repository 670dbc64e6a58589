#pragma once
// Shading modes (mirrored by shaders/shading_modes.glsl). A mode allocates only what it uses.

#include <optional>
#include <string>
#include <string_view>

namespace curette {

enum class ShadingMode { Solid = 0, Phong = 1, Lao = 2, Cao = 3, Dos = 4 };

const char* shadingModeName(ShadingMode mode);
std::optional<ShadingMode> parseShadingMode(std::string_view name);
// "solid, phong, ..." for messages.
std::string shadingModeList();
// Modes that need ambient occlusion volumes (V_o, V_PAO, V_AO).
inline bool usesAmbientOcclusion(ShadingMode m) { return m == ShadingMode::Lao || m == ShadingMode::Cao; }

}  // namespace curette
