#include "render/shading_mode.h"

namespace curette {

namespace {
constexpr ShadingMode allModes[] = {ShadingMode::Solid, ShadingMode::Phong, ShadingMode::Lao, ShadingMode::Cao,
                                    ShadingMode::Dos};
}

const char* shadingModeName(ShadingMode mode) {
    switch (mode) {
        case ShadingMode::Solid: return "solid";
        case ShadingMode::Phong: return "phong";
        case ShadingMode::Lao: return "lao";
        case ShadingMode::Cao: return "cao";
        case ShadingMode::Dos: return "dos";
    }
    return "?";
}

std::optional<ShadingMode> parseShadingMode(std::string_view name) {
    for (ShadingMode m : allModes)
        if (name == shadingModeName(m)) return m;
    return std::nullopt;
}

std::string shadingModeList() {
    std::string list;
    for (ShadingMode m : allModes) list += (list.empty() ? "" : ", ") + std::string(shadingModeName(m));
    return list;
}

}  // namespace curette
