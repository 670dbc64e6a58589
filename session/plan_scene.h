#pragma once
// A state as a scene file: the scene a session or a viewer started from, with the clip meshes where they
// are now (pose, scale, shape, clips_tubes, meshes added and removed), the shading and the lights as they are, every
// setting the panels edited (the value of its last edit, InteractionState::editedKeys: what was read is what
// is written, so the file reads back to the same settings), and optionally the camera, so
// `curette render --scene plan-scene.json` re-creates the carve and the viewer's "Save scene" the picture.
// Every file path in it is made absolute, so the file works from wherever it is written. The one writer of
// scene files (the plan's exports, the viewer).

#include "session/interaction.h"
#include "scene/scene.h"

#include <string>

namespace curette {

// `sceneText` is the original scene file's text (parsed again here, so every key the user wrote is kept). Its
// "removal" is left out: the state's removal is saveScene's to write.
// `camera`: written as the scene's camera (every field, near and far too); null keeps the scene's camera.
std::string planSceneJson(const Scene& scene, const std::string& sceneText, const InteractionState& state,
                          const OrbitCamera* camera = nullptr);

// Writes the state as a scene file at `path` (planSceneJson; atomic) and, when something is drilled, the
// removal beside it (session/removal_file.h: removalFileBeside(path)) named by the scene's "removal" key, so
// the scene loads with it. The one way a state is saved as a scene (the viewer's "save scene", replay
// --save-scene, the plan's exports).
void saveScene(const std::filesystem::path& path, const Scene& scene, const std::string& sceneText, const InteractionState& state,
               const OrbitCamera* camera = nullptr);

// Rotation angles about x, then y, then z (degrees; the scene's "rotation_deg") of a unit quaternion.
glm::dvec3 rotationDegrees(const glm::dquat& orientation);

}  // namespace curette
