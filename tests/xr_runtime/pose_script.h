#pragma once
// The scripted session the test runtime plays (tests/xr_runtime/README.md): per frame the head pose and each
// hand's grip pose and inputs, in the runtime's stage space (metres, +y up, the user looking along -z). After
// the last frame has been submitted the runtime asks the application to exit.

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace curette::xr_test {

struct ScriptPose {
    glm::dvec3 position{0.0};
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};   // w, x, y, z
};

// One hand's controller: its grip pose and the states of its inputs.
struct ScriptHand {
    ScriptPose grip;
    double squeeze = 0.0, trigger = 0.0;   // 0..1
    glm::dvec2 thumbstick{0.0};
    bool thumbstickClick = false, menu = false, a = false, b = false;
};

struct ScriptFrame {
    ScriptPose head;
    std::array<std::optional<ScriptHand>, 2> hands;   // left, right; absent: not tracked
};

// Per-eye field of view in radians: angleLeft, angleRight, angleUp, angleDown (OpenXR's XrFovf).
struct ScriptFov {
    double left = -0.8, right = 0.8, up = 0.8, down = -0.8;
};

struct PoseScript {
    int recommendedWidth = 128, recommendedHeight = 128;
    double ipdM = 0.065;
    std::array<ScriptFov, 2> fov;   // left eye, right eye
    std::string interactionProfile = "/interaction_profiles/khr/simple_controller";
    std::vector<ScriptFrame> frames;   // at least one
};

// Reads the script; throws std::runtime_error naming the file and the key on bad input.
PoseScript readPoseScript(const std::string& path);

}  // namespace curette::xr_test
