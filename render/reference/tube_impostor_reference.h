#pragma once
// The CPU double-precision twin of shaders/tube_impostor.comp: where a ray first meets the impostor tubes
// (render/model/tube_impostors.h), every segment's cylinder (both crossings), the ball at each joint and, with
// caps, the discs at a streamline's ends; a `clipped` predicate stands for the meshes that clip tubes (a
// crossing inside one is skipped, as the shader skips it).

#include "render/model/tube_impostors.h"

#include <functional>
#include <optional>

namespace curette::reference {

struct ImpostorHit {
    double t = 0;              // along the ray (unit direction) from its origin, mm
    glm::dvec3 normal{0.0};    // outward unit normal
    glm::dvec3 color{0.0};     // the point colours interpolated along the segment
};

std::optional<ImpostorHit> firstImpostorHit(const TubeImpostors& impostors, glm::dvec3 origin, glm::dvec3 direction,
                                            const std::function<bool(glm::dvec3)>& clipped = {});

}  // namespace curette::reference
