#include "pose_script.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <stdexcept>

namespace curette::xr_test {

namespace {

struct Reader {
    std::string file;
    [[noreturn]] void fail(const std::string& key, const std::string& expected) const {
        throw std::runtime_error(file + ": " + key + ": expected " + expected);
    }
    double number(const nlohmann::json& j, const std::string& key) const {
        if (!j.is_number()) fail(key, "a number");
        return j.get<double>();
    }
    bool boolean(const nlohmann::json& j, const std::string& key) const {
        if (!j.is_boolean()) fail(key, "true or false");
        return j.get<bool>();
    }
    std::vector<double> numbers(const nlohmann::json& j, const std::string& key, std::size_t n) const {
        if (!j.is_array() || j.size() != n) fail(key, std::to_string(n) + " numbers");
        std::vector<double> v;
        for (std::size_t i = 0; i < n; ++i) v.push_back(number(j[i], key));
        return v;
    }
    ScriptPose pose(const nlohmann::json& j, const std::string& key) const {
        if (!j.is_object()) fail(key, "an object with position and orientation");
        ScriptPose p;
        if (j.contains("position")) {
            std::vector<double> v = numbers(j["position"], key + ".position", 3);
            p.position = {v[0], v[1], v[2]};
        }
        if (j.contains("orientation")) {   // x, y, z, w as OpenXR's XrQuaternionf
            std::vector<double> v = numbers(j["orientation"], key + ".orientation", 4);
            p.orientation = glm::normalize(glm::dquat(v[3], v[0], v[1], v[2]));
        }
        return p;
    }
    ScriptHand hand(const nlohmann::json& j, const std::string& key) const {
        if (!j.is_object()) fail(key, "an object");
        ScriptHand h;
        if (j.contains("grip")) h.grip = pose(j["grip"], key + ".grip");
        if (j.contains("squeeze")) h.squeeze = number(j["squeeze"], key + ".squeeze");
        if (j.contains("trigger")) h.trigger = number(j["trigger"], key + ".trigger");
        if (j.contains("thumbstick")) {
            std::vector<double> v = numbers(j["thumbstick"], key + ".thumbstick", 2);
            h.thumbstick = {v[0], v[1]};
        }
        if (j.contains("thumbstick_click")) h.thumbstickClick = boolean(j["thumbstick_click"], key + ".thumbstick_click");
        if (j.contains("menu")) h.menu = boolean(j["menu"], key + ".menu");
        if (j.contains("a")) h.a = boolean(j["a"], key + ".a");
        if (j.contains("b")) h.b = boolean(j["b"], key + ".b");
        return h;
    }
};

}  // namespace

PoseScript readPoseScript(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot be read");
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(path + ": not JSON (" + e.what() + ")");
    }
    Reader r{path};
    PoseScript s;
    if (j.contains("recommended_size")) {
        std::vector<double> v = r.numbers(j["recommended_size"], "recommended_size", 2);
        s.recommendedWidth = static_cast<int>(v[0]);
        s.recommendedHeight = static_cast<int>(v[1]);
        if (s.recommendedWidth < 1 || s.recommendedHeight < 1) r.fail("recommended_size", "two positive sizes");
    }
    if (j.contains("ipd_m")) s.ipdM = r.number(j["ipd_m"], "ipd_m");
    if (j.contains("fov_rad")) {   // {"left": [l, r, u, d], "right": [...]}
        for (int eye = 0; eye < 2; ++eye) {
            std::string key = eye == 0 ? "left" : "right";
            std::vector<double> v = r.numbers(j["fov_rad"][key], "fov_rad." + key, 4);
            s.fov[static_cast<std::size_t>(eye)] = {v[0], v[1], v[2], v[3]};
        }
    }
    if (j.contains("interaction_profile")) {
        if (!j["interaction_profile"].is_string()) r.fail("interaction_profile", "a path string");
        s.interactionProfile = j["interaction_profile"].get<std::string>();
    }
    if (!j.contains("frames") || !j["frames"].is_array() || j["frames"].empty()) r.fail("frames", "a non-empty array");
    for (std::size_t i = 0; i < j["frames"].size(); ++i) {
        const nlohmann::json& f = j["frames"][i];
        std::string key = "frames[" + std::to_string(i) + "]";
        ScriptFrame frame;
        if (!f.contains("head")) r.fail(key + ".head", "the head pose");
        frame.head = r.pose(f["head"], key + ".head");
        if (f.contains("left")) frame.hands[0] = r.hand(f["left"], key + ".left");
        if (f.contains("right")) frame.hands[1] = r.hand(f["right"], key + ".right");
        s.frames.push_back(frame);
    }
    return s;
}

}  // namespace curette::xr_test
