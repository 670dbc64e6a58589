#pragma once
// The plan as a scene file: the scene a session or a viewer started from, with the clip meshes where they
// are now (pose, scale, meshes added and removed), so `curette render --scene plan-scene.json` re-creates the
// carve. Every file path in it is made absolute, so the file works from wherever it is written.

#include "app/interaction.h"
#include "app/scene.h"

#include <string>

namespace curette {

// `sceneText` is the original scene file's text (parsed again here, so every key the user wrote is kept).
std::string planSceneJson(const Scene& scene, const std::string& sceneText, const InteractionState& state);

// Rotation angles about x, then y, then z (degrees; the scene's "rotation_deg") of a unit quaternion.
glm::dvec3 rotationDegrees(const glm::dquat& orientation);

}  // namespace curette
