#include "render/model/shading_mode.h"

#include "base/enum_table.h"

#include <iterator>

namespace curette {

namespace {
constexpr ShadingModeTraits kModes[] = {
    //  mode               name     AO     dilated slab   tubes in slab pass
    {ShadingMode::Solid, "solid", false, false, false, false, "emission-absorption with the TF colour"},
    {ShadingMode::Phong, "phong", false, false, false, false, "Blinn-Phong with gradient normals"},
    {ShadingMode::Lao, "lao", true, false, false, false, "ambient from LAO recomputed for every voxel (CAO's baseline)"},
    {ShadingMode::Cao, "cao", true, true, false, false, "ambient from Contextual Ambient Occlusion (seed 002)"},
    {ShadingMode::Dos, "dos", false, false, true, true, "directional occlusion shading (seed 001), slab pass"},
    {ShadingMode::Ismos, "ismos", false, false, false, false, "image-space multidirectional occlusion (seed 003) over phong"},
};
static_assert(rowsInEnumOrder(kModes, &ShadingModeTraits::mode, ShadingMode::Count), "kModes is indexed by ShadingMode");
}  // namespace

const ShadingModeTraits& traits(ShadingMode mode) { return kModes[static_cast<std::size_t>(mode)]; }
std::span<const ShadingModeTraits> allShadingModes() { return kModes; }
const char* shadingModeName(ShadingMode mode) { return traits(mode).name; }

std::optional<ShadingMode> parseShadingMode(std::string_view name) {
    for (const ShadingModeTraits& t : kModes)
        if (name == t.name) return t.mode;
    return std::nullopt;
}

std::string shadingModeList() {
    std::string list;
    for (const ShadingModeTraits& t : kModes) list += (list.empty() ? "" : ", ") + std::string(t.name);
    return list;
}

ShadingMode nextShadingMode(ShadingMode mode) {
    return kModes[(static_cast<std::size_t>(mode) + 1) % std::size(kModes)].mode;
}

}  // namespace curette
