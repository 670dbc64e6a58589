// curette's OpenXR test runtime (tests/xr_runtime/README.md): a runtime the Khronos loader loads through
// XR_RUNTIME_JSON, playing a scripted session (pose_script.h) instead of tracking a headset. It implements
// the part of OpenXR 1.0 curette uses: instance and system (one stereo HMD), XR_KHR_opengl_enable (Xlib
// binding; swapchain images are GL textures made in the application's context), reference and action spaces,
// views with each eye's asymmetric field of view, swapchains, the frame loop and the session state machine
// (OpenXR 1.0 spec, 9.3 "Session Lifecycle"), and actions with suggested bindings. At xrEndFrame it reads back
// each submitted projection view and writes it as a PNG, beside the views it located for that frame.
//
// Only the loader negotiation entry point is exported (Loader runtime interface, "Runtime Interface
// Negotiation"); every other function is reached through xrGetInstanceProcAddr.
//
// Environment: CURETTE_XR_TEST_SCRIPT (the pose script, required), CURETTE_XR_TEST_OUT (the folder for the
// PNGs, the views and runtime.log; required), CURETTE_XR_TEST_EGL=1 (also offer XR_MNDX_egl_enable and take
// an EGL context's binding, as Monado does for headless applications).

#include "pose_script.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <epoxy/glx.h>

#define XR_USE_PLATFORM_XLIB
#define XR_USE_PLATFORM_EGL
#define XR_USE_GRAPHICS_API_OPENGL
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>
#include <openxr/openxr_reflection.h>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wnull-dereference"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb_image_write.h>
#pragma GCC diagnostic pop

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

// The loader's negotiation structures (Loader runtime interface; openxr_loader_negotiation.h, which the
// 1.0.20 headers do not ship).
enum XrLoaderInterfaceStructs {
    XR_LOADER_INTERFACE_STRUCT_UNINTIALIZED = 0,
    XR_LOADER_INTERFACE_STRUCT_LOADER_INFO = 1,
    XR_LOADER_INTERFACE_STRUCT_API_LAYER_REQUEST = 2,
    XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST = 3,
};
struct XrNegotiateLoaderInfo {
    XrLoaderInterfaceStructs structType;
    uint32_t structVersion;
    size_t structSize;
    uint32_t minInterfaceVersion;
    uint32_t maxInterfaceVersion;
    XrVersion minApiVersion;
    XrVersion maxApiVersion;
};
struct XrNegotiateRuntimeRequest {
    XrLoaderInterfaceStructs structType;
    uint32_t structVersion;
    size_t structSize;
    uint32_t runtimeInterfaceVersion;
    XrVersion runtimeApiVersion;
    PFN_xrGetInstanceProcAddr getInstanceProcAddr;
};
constexpr uint32_t kLoaderInfoStructVersion = 1, kRuntimeInfoStructVersion = 1, kLoaderRuntimeVersion = 1;

namespace curette::xr_test {
namespace {

constexpr XrSystemId kSystemId = 1;
constexpr XrTime kFirstDisplayTime = 1'000'000'000;      // 1 s
constexpr XrDuration kDisplayPeriod = 11'111'111;        // 90 Hz
constexpr std::uint32_t kImagesPerSwapchain = 3;
constexpr std::int64_t kSwapchainFormats[] = {GL_SRGB8_ALPHA8, GL_RGBA8};

struct Pose {
    glm::dvec3 position{0.0};
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};
};
Pose compose(const Pose& a, const Pose& b) { return {a.position + a.orientation * b.position, a.orientation * b.orientation}; }
Pose inverse(const Pose& a) {
    glm::dquat q = glm::conjugate(a.orientation);
    return {-(q * a.position), q};
}
Pose fromXr(const XrPosef& p) {
    return {{p.position.x, p.position.y, p.position.z}, glm::normalize(glm::dquat(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z))};
}
XrPosef toXr(const Pose& p) {
    XrPosef x;
    x.position = {static_cast<float>(p.position.x), static_cast<float>(p.position.y), static_cast<float>(p.position.z)};
    x.orientation = {static_cast<float>(p.orientation.x), static_cast<float>(p.orientation.y), static_cast<float>(p.orientation.z),
                     static_cast<float>(p.orientation.w)};
    return x;
}
Pose fromScript(const ScriptPose& p) { return {p.position, p.orientation}; }

struct Swapchain {
    std::int64_t format = 0;
    std::uint32_t width = 0, height = 0;
    std::vector<GLuint> textures;
    std::uint32_t next = 0;                // the image the next acquire returns
    std::deque<std::uint32_t> acquired;   // acquired, not released, oldest first
    bool waited = false;
    int lastReleased = -1;
};

struct Action {
    std::string name;
    XrActionType type{};
    std::vector<XrPath> subactionPaths;
    XrActionSet set = XR_NULL_HANDLE;
};

struct Space {
    enum class Kind { Reference, Action } kind = Kind::Reference;
    XrReferenceSpaceType reference{};
    XrAction action = XR_NULL_HANDLE;
    XrPath subactionPath = XR_NULL_PATH;
    Pose offset;
};

// The values one hand's bound input gives, once synchronised.
struct SyncedValue {
    bool active = false;
    float value = 0.0f;      // boolean and float actions
    glm::vec2 vector{0.0f};  // vector2f actions
    bool changed = false;
    XrTime lastChange = 0;
};

struct Runtime {
    PoseScript script;
    std::filesystem::path out;
    std::ofstream log;
    bool instance = false, requirementsQueried = false;
    bool eglEnabled = false;   // the application enabled XR_MNDX_egl_enable
    XrInstance instanceHandle = XR_NULL_HANDLE;
    std::uint64_t nextHandle = 1;
    std::vector<std::string> paths;   // XrPath p is paths[p - 1]

    // The session.
    bool session = false, running = false, exitRequested = false;
    XrSession sessionHandle = XR_NULL_HANDLE;
    XrSessionState state = XR_SESSION_STATE_UNKNOWN;
    std::deque<XrEventDataBuffer> events;
    std::map<std::uint64_t, Swapchain> swapchains;
    std::map<std::uint64_t, Space> spaces;
    std::map<std::uint64_t, std::string> actionSets;
    std::map<std::uint64_t, Action> actions;
    std::map<XrPath, std::vector<std::pair<XrAction, XrPath>>> suggested;   // profile -> (action, binding)
    bool attached = false, profileAnnounced = false;
    std::map<std::pair<std::uint64_t, int>, SyncedValue> synced;   // (action, hand or -1) -> value

    // The frame loop.
    std::int64_t waited = 0;                // xrWaitFrame calls
    std::int64_t begun = -1;                // the frame xrBeginFrame began (-1: none under way)
    XrTime lastWaitedTime = 0;
    XrTime firstRenderTime = -1;            // the first display time with shouldRender
    int framesWritten = 0;
    // What xrLocateViews handed out, per display time, and the kind of space they were located in.
    struct Located {
        std::array<XrView, 2> views;
        std::string space;   // "stage", "local", "view", "action"
    };
    std::map<XrTime, Located> located;

    std::uint64_t handle() { return nextHandle++; }

    void note(const std::string& line) {
        log << line << '\n';
        log.flush();
    }

    void queueState(XrSessionState s) {
        state = s;
        XrEventDataBuffer buffer{};
        auto* e = reinterpret_cast<XrEventDataSessionStateChanged*>(&buffer);
        e->type = XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED;
        e->next = nullptr;
        e->session = sessionHandle;
        e->state = s;
        e->time = lastWaitedTime;
        events.push_back(buffer);
        static const std::map<XrSessionState, const char*> names{
            {XR_SESSION_STATE_IDLE, "IDLE"},       {XR_SESSION_STATE_READY, "READY"},     {XR_SESSION_STATE_SYNCHRONIZED, "SYNCHRONIZED"},
            {XR_SESSION_STATE_VISIBLE, "VISIBLE"}, {XR_SESSION_STATE_FOCUSED, "FOCUSED"}, {XR_SESSION_STATE_STOPPING, "STOPPING"},
            {XR_SESSION_STATE_EXITING, "EXITING"}, {XR_SESSION_STATE_LOSS_PENDING, "LOSS_PENDING"}};
        note(std::string("state ") + names.at(s));
    }

    // Down from FOCUSED to STOPPING once the script is done or the application asks to exit (spec 9.3).
    void stop() {
        if (exitRequested) return;
        exitRequested = true;
        if (state == XR_SESSION_STATE_FOCUSED) queueState(XR_SESSION_STATE_VISIBLE);
        if (state == XR_SESSION_STATE_VISIBLE) queueState(XR_SESSION_STATE_SYNCHRONIZED);
        if (state == XR_SESSION_STATE_SYNCHRONIZED || state == XR_SESSION_STATE_READY) queueState(XR_SESSION_STATE_STOPPING);
    }

    // The script frame a display time shows: frame 0 up to the first rendered time, then one a period.
    std::size_t frameAt(XrTime t) const {
        if (firstRenderTime < 0 || t <= firstRenderTime) return 0;
        std::int64_t i = (t - firstRenderTime + kDisplayPeriod / 2) / kDisplayPeriod;
        return static_cast<std::size_t>(std::min<std::int64_t>(i, static_cast<std::int64_t>(script.frames.size()) - 1));
    }

    Pose head(XrTime t) const { return fromScript(script.frames[frameAt(t)].head); }

    // The eye `eye` (0 left) at time t, in the stage: the head moved half the IPD along its own x axis.
    Pose eye(XrTime t, int eye) const {
        Pose h = head(t);
        return compose(h, {{(eye == 0 ? -0.5 : 0.5) * script.ipdM, 0.0, 0.0}, glm::dquat(1.0, 0.0, 0.0, 0.0)});
    }

    const std::string& pathString(XrPath p) const { return paths.at(static_cast<std::size_t>(p - 1)); }

    int handOf(XrPath p) const {
        if (p == XR_NULL_PATH) return -1;
        const std::string& s = pathString(p);
        if (s.rfind("/user/hand/left", 0) == 0) return 0;
        if (s.rfind("/user/hand/right", 0) == 0) return 1;
        return -2;
    }

    // Where a space is in the stage at time t; nullopt when it is not tracked.
    std::optional<Pose> inStage(const Space& s, XrTime t) const {
        if (s.kind == Space::Kind::Reference) {
            if (s.reference == XR_REFERENCE_SPACE_TYPE_VIEW) return compose(head(t), s.offset);
            return s.offset;   // LOCAL and STAGE: the same origin in this runtime
        }
        const ScriptFrame& f = script.frames[frameAt(t)];
        int hand = handOf(s.subactionPath);
        for (int h : {0, 1}) {
            if (hand >= 0 && h != hand) continue;
            if (!f.hands[static_cast<std::size_t>(h)] || !bound(reinterpret_cast<std::uint64_t>(s.action), h)) continue;
            return compose(fromScript(f.hands[static_cast<std::size_t>(h)]->grip), s.offset);
        }
        return std::nullopt;
    }

    // The bindings of the script's interaction profile for an action and hand.
    std::vector<std::string> bindings(std::uint64_t action, int hand) const {
        std::vector<std::string> found;
        auto profile = std::find(paths.begin(), paths.end(), script.interactionProfile);
        if (profile == paths.end()) return found;
        auto it = suggested.find(static_cast<XrPath>(profile - paths.begin() + 1));
        if (it == suggested.end()) return found;
        for (const auto& [a, binding] : it->second)
            if (reinterpret_cast<std::uint64_t>(a) == action && handOf(binding) == hand) found.push_back(pathString(binding));
        return found;
    }
    bool bound(std::uint64_t action, int hand) const { return attached && !bindings(action, hand).empty(); }

    // The value of one bound input of a scripted hand: a float for buttons and axes, a vector for sticks.
    static bool inputValue(const ScriptHand& h, const std::string& binding, float& value, glm::vec2& vector) {
        std::string input = binding.substr(binding.find("/input/") + 7);
        auto is = [&](std::initializer_list<const char*> names) {
            for (const char* n : names)
                if (input == n) return true;
            return false;
        };
        if (is({"squeeze/value", "squeeze/click", "squeeze/force"})) value = static_cast<float>(h.squeeze);
        else if (is({"trigger/value", "trigger/click", "select/click"})) value = static_cast<float>(h.trigger);
        else if (is({"thumbstick", "trackpad"})) vector = glm::vec2(h.thumbstick);
        else if (is({"thumbstick/x", "trackpad/x"})) value = static_cast<float>(h.thumbstick.x);
        else if (is({"thumbstick/y", "trackpad/y"})) value = static_cast<float>(h.thumbstick.y);
        else if (is({"thumbstick/click", "trackpad/click"})) value = h.thumbstickClick ? 1.0f : 0.0f;
        else if (is({"menu/click", "system/click"})) value = h.menu ? 1.0f : 0.0f;
        else if (is({"a/click", "x/click"})) value = h.a ? 1.0f : 0.0f;
        else if (is({"b/click", "y/click"})) value = h.b ? 1.0f : 0.0f;
        else if (is({"grip/pose", "aim/pose"})) value = 1.0f;
        else return false;
        return true;
    }

    // xrSyncActions: every action's value for each hand and for both (OpenXR 11.5: booleans OR, floats and
    // vectors the largest magnitude).
    void sync() {
        const ScriptFrame& f = script.frames[frameAt(lastWaitedTime)];
        for (const auto& [id, action] : actions) {
            for (int hand : {-1, 0, 1}) {
                SyncedValue v;
                for (int h : {0, 1}) {
                    if ((hand >= 0 && h != hand) || !f.hands[static_cast<std::size_t>(h)]) continue;
                    for (const std::string& b : bindings(id, h)) {
                        float value = 0.0f;
                        glm::vec2 vector(0.0f);
                        if (!inputValue(*f.hands[static_cast<std::size_t>(h)], b, value, vector)) continue;
                        v.active = true;
                        if (action.type == XR_ACTION_TYPE_BOOLEAN_INPUT) value = value > 0.5f ? 1.0f : 0.0f;
                        if (std::abs(value) > std::abs(v.value)) v.value = value;
                        if (glm::length(vector) > glm::length(v.vector)) v.vector = vector;
                    }
                }
                SyncedValue& old = synced[{id, hand}];
                v.changed = old.active && v.active && (old.value != v.value || old.vector != v.vector);
                v.lastChange = v.changed ? lastWaitedTime : old.lastChange;
                old = v;
            }
        }
    }

    // Reads back the submitted views of a projection layer and writes them, with the views located for the
    // frame, as frame_NNNNNN_{left,right}.png and frame_NNNNNN_views.json.
    void capture(const XrCompositionLayerProjection& layer, XrTime t) {
        std::size_t frame = frameAt(t);
        char stem[32];
        std::snprintf(stem, sizeof stem, "frame_%06zu", frame);
        nlohmann::json views = nlohmann::json::array();
        for (std::uint32_t v = 0; v < layer.viewCount && v < 2; ++v) {
            const XrCompositionLayerProjectionView& view = layer.views[v];
            Swapchain& sc = swapchains.at(reinterpret_cast<std::uint64_t>(view.subImage.swapchain));
            if (sc.lastReleased < 0) {
                note("error: a projection view's swapchain has no released image");
                continue;
            }
            const XrRect2Di& r = view.subImage.imageRect;
            std::vector<std::uint8_t> pixels(static_cast<std::size_t>(r.extent.width) * static_cast<std::size_t>(r.extent.height) * 4);
            glPixelStorei(GL_PACK_ALIGNMENT, 1);
            glGetTextureSubImage(sc.textures[static_cast<std::size_t>(sc.lastReleased)], 0, r.offset.x, r.offset.y, 0, r.extent.width,
                                 r.extent.height, 1, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(pixels.size()), pixels.data());
            // GL rows run bottom-up; a PNG's top-down.
            std::vector<std::uint8_t> flipped(pixels.size());
            const std::size_t row = static_cast<std::size_t>(r.extent.width) * 4;
            for (int y = 0; y < r.extent.height; ++y)
                std::memcpy(flipped.data() + static_cast<std::size_t>(y) * row,
                            pixels.data() + static_cast<std::size_t>(r.extent.height - 1 - y) * row, row);
            std::string name = std::string(stem) + (v == 0 ? "_left.png" : "_right.png");
            if (!stbi_write_png((out / name).c_str(), r.extent.width, r.extent.height, 4, flipped.data(), static_cast<int>(row)))
                note("error: cannot write " + name);
            // The view exactly as xrLocateViews gave it to the application (floats), else as the script has it.
            XrView given{};
            if (auto it = located.find(t); it != located.end()) given = it->second.views[v];
            else {
                given.pose = toXr(eye(t, static_cast<int>(v)));
                const ScriptFov& f = script.fov[v];
                given.fov = {static_cast<float>(f.left), static_cast<float>(f.right), static_cast<float>(f.up), static_cast<float>(f.down)};
                note("error: frame " + std::to_string(frame) + " was submitted without its views located");
            }
            const XrPosef& p = given.pose;
            views.push_back({{"position_m", {p.position.x, p.position.y, p.position.z}},
                             {"orientation", {p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w}},
                             {"fov_rad", {given.fov.angleLeft, given.fov.angleRight, given.fov.angleUp, given.fov.angleDown}},
                             {"submitted_fov_rad", {view.fov.angleLeft, view.fov.angleRight, view.fov.angleUp, view.fov.angleDown}},
                             {"image_rect", {r.offset.x, r.offset.y, r.extent.width, r.extent.height}}});
        }
        auto it = located.find(t);
        nlohmann::json doc = {{"space", it != located.end() ? it->second.space : std::string("stage")},
                              {"recommended_size", {script.recommendedWidth, script.recommendedHeight}},
                              {"views", views}};
        std::ofstream(out / (std::string(stem) + "_views.json")) << doc.dump(2) << '\n';
        ++framesWritten;
        note("frame " + std::to_string(frame) + " written");
        if (frame + 1 == script.frames.size()) stop();
    }
};

Runtime* runtime = nullptr;

template <typename T>
T* asHandle(std::uint64_t id) {
    return reinterpret_cast<T*>(id);
}
template <typename H>
std::uint64_t idOf(H handle) {
    return reinterpret_cast<std::uint64_t>(handle);
}

bool isInstance(XrInstance i) { return runtime && runtime->instance && i == runtime->instanceHandle; }
bool isSession(XrSession s) { return runtime && runtime->session && s == runtime->sessionHandle; }

// Two-call idiom (OpenXR 2.11): count only when capacity is 0, else copy.
template <typename T, typename F>
XrResult fill(std::uint32_t capacity, std::uint32_t* count, T* out, std::size_t n, F&& write) {
    if (!count) return XR_ERROR_VALIDATION_FAILURE;
    *count = static_cast<std::uint32_t>(n);
    if (capacity == 0) return XR_SUCCESS;
    if (capacity < n || !out) return XR_ERROR_SIZE_INSUFFICIENT;
    for (std::size_t i = 0; i < n; ++i) write(out[i], i);
    return XR_SUCCESS;
}

// The extensions offered: XR_KHR_opengl_enable, and in the EGL mode XR_MNDX_egl_enable.
std::vector<const char*> offeredExtensions() {
    std::vector<const char*> names{XR_KHR_OPENGL_ENABLE_EXTENSION_NAME};
    const char* egl = std::getenv("CURETTE_XR_TEST_EGL");
    if (egl && std::strcmp(egl, "1") == 0) names.push_back(XR_MNDX_EGL_ENABLE_EXTENSION_NAME);
    return names;
}

XrResult XRAPI_CALL enumerateInstanceExtensionProperties(const char* layerName, std::uint32_t capacity, std::uint32_t* count,
                                                         XrExtensionProperties* properties) {
    if (layerName) return XR_ERROR_API_LAYER_NOT_PRESENT;
    const std::vector<const char*> names = offeredExtensions();
    return fill(capacity, count, properties, names.size(), [&](XrExtensionProperties& p, std::size_t i) {
        std::snprintf(p.extensionName, sizeof p.extensionName, "%s", names[i]);
        p.extensionVersion = 1;
    });
}

XrResult XRAPI_CALL createInstance(const XrInstanceCreateInfo* info, XrInstance* instance) {
    if (!info || !instance) return XR_ERROR_VALIDATION_FAILURE;
    if (runtime && runtime->instance) return XR_ERROR_LIMIT_REACHED;
    const std::vector<const char*> offered = offeredExtensions();
    bool eglEnabled = false;
    for (std::uint32_t i = 0; i < info->enabledExtensionCount; ++i) {
        const char* name = info->enabledExtensionNames[i];
        if (std::none_of(offered.begin(), offered.end(), [&](const char* o) { return std::strcmp(o, name) == 0; })) return XR_ERROR_EXTENSION_NOT_PRESENT;
        eglEnabled = eglEnabled || std::strcmp(name, XR_MNDX_EGL_ENABLE_EXTENSION_NAME) == 0;
    }
    const char* scriptPath = std::getenv("CURETTE_XR_TEST_SCRIPT");
    const char* outPath = std::getenv("CURETTE_XR_TEST_OUT");
    if (!scriptPath || !outPath) {
        std::fprintf(stderr, "curette XR test runtime: set CURETTE_XR_TEST_SCRIPT (the pose script) and CURETTE_XR_TEST_OUT (a folder)\n");
        return XR_ERROR_INITIALIZATION_FAILED;
    }
    auto r = std::make_unique<Runtime>();
    try {
        r->script = readPoseScript(scriptPath);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "curette XR test runtime: %s\n", e.what());
        return XR_ERROR_INITIALIZATION_FAILED;
    }
    r->out = outPath;
    r->eglEnabled = eglEnabled;
    std::error_code ec;
    std::filesystem::create_directories(r->out, ec);
    r->log.open(r->out / "runtime.log");
    if (!r->log) return XR_ERROR_INITIALIZATION_FAILED;
    r->instance = true;
    r->instanceHandle = asHandle<XrInstance_T>(r->handle());
    r->note(std::string("instance ") + info->applicationInfo.applicationName);
    delete runtime;
    runtime = r.release();
    *instance = runtime->instanceHandle;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL destroyInstance(XrInstance instance) {
    if (!isInstance(instance)) return XR_ERROR_HANDLE_INVALID;
    runtime->note("instance destroyed");
    delete runtime;
    runtime = nullptr;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL getInstanceProperties(XrInstance instance, XrInstanceProperties* properties) {
    if (!isInstance(instance)) return XR_ERROR_HANDLE_INVALID;
    properties->runtimeVersion = XR_MAKE_VERSION(0, 1, 0);
    std::snprintf(properties->runtimeName, sizeof properties->runtimeName, "curette test runtime (scripted, no headset)");
    return XR_SUCCESS;
}

XrResult XRAPI_CALL pollEvent(XrInstance instance, XrEventDataBuffer* event) {
    if (!isInstance(instance)) return XR_ERROR_HANDLE_INVALID;
    if (runtime->events.empty()) return XR_EVENT_UNAVAILABLE;
    *event = runtime->events.front();
    runtime->events.pop_front();
    return XR_SUCCESS;
}

XrResult XRAPI_CALL resultToString(XrInstance, XrResult value, char buffer[XR_MAX_RESULT_STRING_SIZE]) {
#define CURETTE_RESULT_CASE(name, number) \
    case name: std::snprintf(buffer, XR_MAX_RESULT_STRING_SIZE, "%s", #name); return XR_SUCCESS;
    switch (value) {
        XR_LIST_ENUM_XrResult(CURETTE_RESULT_CASE)
        default: break;
    }
#undef CURETTE_RESULT_CASE
    std::snprintf(buffer, XR_MAX_RESULT_STRING_SIZE, "XR_UNKNOWN_%s_%d", value < 0 ? "FAILURE" : "SUCCESS", static_cast<int>(value));
    return XR_SUCCESS;
}

XrResult XRAPI_CALL structureTypeToString(XrInstance, XrStructureType value, char buffer[XR_MAX_STRUCTURE_NAME_SIZE]) {
#define CURETTE_TYPE_CASE(name, number) \
    case name: std::snprintf(buffer, XR_MAX_STRUCTURE_NAME_SIZE, "%s", #name); return XR_SUCCESS;
    switch (value) {
        XR_LIST_ENUM_XrStructureType(CURETTE_TYPE_CASE)
        default: break;
    }
#undef CURETTE_TYPE_CASE
    std::snprintf(buffer, XR_MAX_STRUCTURE_NAME_SIZE, "XR_UNKNOWN_STRUCTURE_TYPE_%d", static_cast<int>(value));
    return XR_SUCCESS;
}

XrResult XRAPI_CALL getSystem(XrInstance instance, const XrSystemGetInfo* info, XrSystemId* system) {
    if (!isInstance(instance)) return XR_ERROR_HANDLE_INVALID;
    if (info->formFactor != XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY) return XR_ERROR_FORM_FACTOR_UNSUPPORTED;
    *system = kSystemId;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL getSystemProperties(XrInstance instance, XrSystemId system, XrSystemProperties* properties) {
    if (!isInstance(instance)) return XR_ERROR_HANDLE_INVALID;
    if (system != kSystemId) return XR_ERROR_SYSTEM_INVALID;
    properties->systemId = kSystemId;
    properties->vendorId = 0;
    std::snprintf(properties->systemName, sizeof properties->systemName, "curette scripted HMD");
    properties->graphicsProperties.maxSwapchainImageWidth = 4096;
    properties->graphicsProperties.maxSwapchainImageHeight = 4096;
    properties->graphicsProperties.maxLayerCount = XR_MIN_COMPOSITION_LAYERS_SUPPORTED;
    properties->trackingProperties.orientationTracking = XR_TRUE;
    properties->trackingProperties.positionTracking = XR_TRUE;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL enumerateViewConfigurations(XrInstance instance, XrSystemId system, std::uint32_t capacity, std::uint32_t* count,
                                                XrViewConfigurationType* types) {
    if (!isInstance(instance)) return XR_ERROR_HANDLE_INVALID;
    if (system != kSystemId) return XR_ERROR_SYSTEM_INVALID;
    return fill(capacity, count, types, 1, [](XrViewConfigurationType& t, std::size_t) { t = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO; });
}

XrResult XRAPI_CALL getViewConfigurationProperties(XrInstance instance, XrSystemId system, XrViewConfigurationType type,
                                                   XrViewConfigurationProperties* properties) {
    if (!isInstance(instance)) return XR_ERROR_HANDLE_INVALID;
    if (system != kSystemId) return XR_ERROR_SYSTEM_INVALID;
    if (type != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
    properties->viewConfigurationType = type;
    properties->fovMutable = XR_TRUE;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL enumerateViewConfigurationViews(XrInstance instance, XrSystemId system, XrViewConfigurationType type, std::uint32_t capacity,
                                                    std::uint32_t* count, XrViewConfigurationView* views) {
    if (!isInstance(instance)) return XR_ERROR_HANDLE_INVALID;
    if (system != kSystemId) return XR_ERROR_SYSTEM_INVALID;
    if (type != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
    const PoseScript& s = runtime->script;
    return fill(capacity, count, views, 2, [&](XrViewConfigurationView& v, std::size_t) {
        v.recommendedImageRectWidth = static_cast<std::uint32_t>(s.recommendedWidth);
        v.recommendedImageRectHeight = static_cast<std::uint32_t>(s.recommendedHeight);
        v.maxImageRectWidth = 4096;
        v.maxImageRectHeight = 4096;
        v.recommendedSwapchainSampleCount = 1;
        v.maxSwapchainSampleCount = 1;
    });
}

XrResult XRAPI_CALL enumerateEnvironmentBlendModes(XrInstance instance, XrSystemId system, XrViewConfigurationType type, std::uint32_t capacity,
                                                   std::uint32_t* count, XrEnvironmentBlendMode* modes) {
    if (!isInstance(instance)) return XR_ERROR_HANDLE_INVALID;
    if (system != kSystemId) return XR_ERROR_SYSTEM_INVALID;
    if (type != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
    return fill(capacity, count, modes, 1, [](XrEnvironmentBlendMode& m, std::size_t) { m = XR_ENVIRONMENT_BLEND_MODE_OPAQUE; });
}

XrResult XRAPI_CALL getOpenGLGraphicsRequirements(XrInstance instance, XrSystemId system, XrGraphicsRequirementsOpenGLKHR* requirements) {
    if (!isInstance(instance)) return XR_ERROR_HANDLE_INVALID;
    if (system != kSystemId) return XR_ERROR_SYSTEM_INVALID;
    requirements->minApiVersionSupported = XR_MAKE_VERSION(4, 5, 0);
    requirements->maxApiVersionSupported = XR_MAKE_VERSION(4, 6, 0);
    runtime->requirementsQueried = true;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL createSession(XrInstance instance, const XrSessionCreateInfo* info, XrSession* session) {
    if (!isInstance(instance)) return XR_ERROR_HANDLE_INVALID;
    if (info->systemId != kSystemId) return XR_ERROR_SYSTEM_INVALID;
    if (!runtime->requirementsQueried) return XR_ERROR_GRAPHICS_REQUIREMENTS_CALL_MISSING;
    if (runtime->session) return XR_ERROR_LIMIT_REACHED;
    const auto* header = static_cast<const XrBaseInStructure*>(info->next);
    if (!header) return XR_ERROR_GRAPHICS_DEVICE_INVALID;
    // The swapchain images are made in, and read back from, the application's context: it must be current.
    if (header->type == XR_TYPE_GRAPHICS_BINDING_OPENGL_XLIB_KHR) {
        const auto* binding = reinterpret_cast<const XrGraphicsBindingOpenGLXlibKHR*>(header);
        if (!binding->glxContext || glXGetCurrentContext() != binding->glxContext) {
            runtime->note("error: the binding's GLX context is not current");
            return XR_ERROR_GRAPHICS_DEVICE_INVALID;
        }
        runtime->note("session binding: GLX");
    } else if (header->type == XR_TYPE_GRAPHICS_BINDING_EGL_MNDX) {
        if (!runtime->eglEnabled) {
            runtime->note("error: an EGL binding without XR_MNDX_egl_enable enabled");
            return XR_ERROR_GRAPHICS_DEVICE_INVALID;
        }
        const auto* binding = reinterpret_cast<const XrGraphicsBindingEGLMNDX*>(header);
        if (!binding->getProcAddress || !binding->display || !binding->context || eglGetCurrentContext() != binding->context ||
            eglGetCurrentDisplay() != binding->display) {
            runtime->note("error: the binding's EGL context is not current");
            return XR_ERROR_GRAPHICS_DEVICE_INVALID;
        }
        runtime->note("session binding: EGL");
    } else {
        return XR_ERROR_GRAPHICS_DEVICE_INVALID;
    }
    runtime->session = true;
    runtime->sessionHandle = asHandle<XrSession_T>(runtime->handle());
    *session = runtime->sessionHandle;
    runtime->note("session created");
    runtime->queueState(XR_SESSION_STATE_IDLE);
    runtime->queueState(XR_SESSION_STATE_READY);
    return XR_SUCCESS;
}

XrResult XRAPI_CALL destroySession(XrSession session) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    for (auto& [id, sc] : runtime->swapchains) glDeleteTextures(static_cast<GLsizei>(sc.textures.size()), sc.textures.data());
    runtime->swapchains.clear();
    runtime->spaces.clear();
    runtime->session = false;
    runtime->note("session destroyed");
    return XR_SUCCESS;
}

XrResult XRAPI_CALL beginSession(XrSession session, const XrSessionBeginInfo* info) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    if (runtime->running) return XR_ERROR_SESSION_RUNNING;
    if (runtime->state != XR_SESSION_STATE_READY) return XR_ERROR_SESSION_NOT_READY;
    if (info->primaryViewConfigurationType != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
    runtime->running = true;
    runtime->note("session begun");
    return XR_SUCCESS;
}

XrResult XRAPI_CALL endSession(XrSession session) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    if (!runtime->running) return XR_ERROR_SESSION_NOT_RUNNING;
    if (runtime->state != XR_SESSION_STATE_STOPPING) return XR_ERROR_SESSION_NOT_STOPPING;
    runtime->running = false;
    runtime->note("session ended");
    runtime->queueState(XR_SESSION_STATE_IDLE);
    if (runtime->exitRequested) runtime->queueState(XR_SESSION_STATE_EXITING);
    return XR_SUCCESS;
}

XrResult XRAPI_CALL requestExitSession(XrSession session) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    if (!runtime->running) return XR_ERROR_SESSION_NOT_RUNNING;
    runtime->note("exit requested by the application");
    runtime->stop();
    return XR_SUCCESS;
}

constexpr XrReferenceSpaceType kReferenceSpaces[] = {XR_REFERENCE_SPACE_TYPE_VIEW, XR_REFERENCE_SPACE_TYPE_LOCAL, XR_REFERENCE_SPACE_TYPE_STAGE};

XrResult XRAPI_CALL enumerateReferenceSpaces(XrSession session, std::uint32_t capacity, std::uint32_t* count, XrReferenceSpaceType* spaces) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    return fill(capacity, count, spaces, std::size(kReferenceSpaces), [](XrReferenceSpaceType& t, std::size_t i) { t = kReferenceSpaces[i]; });
}

XrResult XRAPI_CALL createReferenceSpace(XrSession session, const XrReferenceSpaceCreateInfo* info, XrSpace* space) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    if (std::find(std::begin(kReferenceSpaces), std::end(kReferenceSpaces), info->referenceSpaceType) == std::end(kReferenceSpaces))
        return XR_ERROR_REFERENCE_SPACE_UNSUPPORTED;
    Space s;
    s.reference = info->referenceSpaceType;
    s.offset = fromXr(info->poseInReferenceSpace);
    std::uint64_t id = runtime->handle();
    runtime->spaces[id] = s;
    *space = asHandle<XrSpace_T>(id);
    return XR_SUCCESS;
}

XrResult XRAPI_CALL getReferenceSpaceBoundsRect(XrSession session, XrReferenceSpaceType, XrExtent2Df* bounds) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    *bounds = {0.0f, 0.0f};
    return XR_SPACE_BOUNDS_UNAVAILABLE;
}

XrResult XRAPI_CALL createActionSpace(XrSession session, const XrActionSpaceCreateInfo* info, XrSpace* space) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    auto a = runtime->actions.find(idOf(info->action));
    if (a == runtime->actions.end()) return XR_ERROR_HANDLE_INVALID;
    if (a->second.type != XR_ACTION_TYPE_POSE_INPUT) return XR_ERROR_ACTION_TYPE_MISMATCH;
    Space s;
    s.kind = Space::Kind::Action;
    s.action = info->action;
    s.subactionPath = info->subactionPath;
    s.offset = fromXr(info->poseInActionSpace);
    std::uint64_t id = runtime->handle();
    runtime->spaces[id] = s;
    *space = asHandle<XrSpace_T>(id);
    return XR_SUCCESS;
}

XrResult XRAPI_CALL locateSpace(XrSpace space, XrSpace baseSpace, XrTime time, XrSpaceLocation* location) {
    if (!runtime) return XR_ERROR_HANDLE_INVALID;
    auto s = runtime->spaces.find(idOf(space)), b = runtime->spaces.find(idOf(baseSpace));
    if (s == runtime->spaces.end() || b == runtime->spaces.end()) return XR_ERROR_HANDLE_INVALID;
    if (time <= 0) return XR_ERROR_TIME_INVALID;
    std::optional<Pose> ps = runtime->inStage(s->second, time), pb = runtime->inStage(b->second, time);
    if (!ps || !pb) {
        location->locationFlags = 0;
        return XR_SUCCESS;
    }
    location->pose = toXr(compose(inverse(*pb), *ps));
    location->locationFlags = XR_SPACE_LOCATION_ORIENTATION_VALID_BIT | XR_SPACE_LOCATION_POSITION_VALID_BIT |
                              XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT | XR_SPACE_LOCATION_POSITION_TRACKED_BIT;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL destroySpace(XrSpace space) {
    if (!runtime || !runtime->spaces.erase(idOf(space))) return XR_ERROR_HANDLE_INVALID;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL locateViews(XrSession session, const XrViewLocateInfo* info, XrViewState* state, std::uint32_t capacity, std::uint32_t* count,
                                XrView* views) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    if (info->viewConfigurationType != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
    auto base = runtime->spaces.find(idOf(info->space));
    if (base == runtime->spaces.end()) return XR_ERROR_HANDLE_INVALID;
    if (info->displayTime <= 0) return XR_ERROR_TIME_INVALID;
    std::optional<Pose> pb = runtime->inStage(base->second, info->displayTime);
    state->viewStateFlags = pb ? XR_VIEW_STATE_ORIENTATION_VALID_BIT | XR_VIEW_STATE_POSITION_VALID_BIT | XR_VIEW_STATE_ORIENTATION_TRACKED_BIT |
                                     XR_VIEW_STATE_POSITION_TRACKED_BIT
                               : 0;
    XrResult result = fill(capacity, count, views, 2, [&](XrView& v, std::size_t eye) {
        v.pose = toXr(pb ? compose(inverse(*pb), runtime->eye(info->displayTime, static_cast<int>(eye))) : Pose{});
        const ScriptFov& f = runtime->script.fov[eye];
        v.fov = {static_cast<float>(f.left), static_cast<float>(f.right), static_cast<float>(f.up), static_cast<float>(f.down)};
    });
    if (result == XR_SUCCESS && capacity >= 2) {
        const Space& s = base->second;
        std::string kind = s.kind == Space::Kind::Action ? "action"
                           : s.reference == XR_REFERENCE_SPACE_TYPE_STAGE ? "stage"
                           : s.reference == XR_REFERENCE_SPACE_TYPE_LOCAL ? "local"
                                                                          : "view";
        runtime->located[info->displayTime] = {{views[0], views[1]}, kind};
    }
    return result;
}

XrResult XRAPI_CALL enumerateSwapchainFormats(XrSession session, std::uint32_t capacity, std::uint32_t* count, std::int64_t* formats) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    return fill(capacity, count, formats, std::size(kSwapchainFormats), [](std::int64_t& f, std::size_t i) { f = kSwapchainFormats[i]; });
}

XrResult XRAPI_CALL createSwapchain(XrSession session, const XrSwapchainCreateInfo* info, XrSwapchain* swapchain) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    if (std::find(std::begin(kSwapchainFormats), std::end(kSwapchainFormats), info->format) == std::end(kSwapchainFormats))
        return XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED;
    if (info->sampleCount != 1 || info->faceCount != 1 || info->arraySize != 1 || info->mipCount != 1 || info->width == 0 || info->height == 0 ||
        info->width > 4096 || info->height > 4096)
        return XR_ERROR_FEATURE_UNSUPPORTED;
    Swapchain sc;
    sc.format = info->format;
    sc.width = info->width;
    sc.height = info->height;
    sc.textures.resize(kImagesPerSwapchain);
    glCreateTextures(GL_TEXTURE_2D, static_cast<GLsizei>(sc.textures.size()), sc.textures.data());
    for (GLuint t : sc.textures)
        glTextureStorage2D(t, 1, static_cast<GLenum>(info->format), static_cast<GLsizei>(info->width), static_cast<GLsizei>(info->height));
    std::uint64_t id = runtime->handle();
    runtime->swapchains[id] = std::move(sc);
    *swapchain = asHandle<XrSwapchain_T>(id);
    runtime->note("swapchain " + std::to_string(info->width) + "x" + std::to_string(info->height));
    return XR_SUCCESS;
}

XrResult XRAPI_CALL destroySwapchain(XrSwapchain swapchain) {
    if (!runtime) return XR_ERROR_HANDLE_INVALID;
    auto it = runtime->swapchains.find(idOf(swapchain));
    if (it == runtime->swapchains.end()) return XR_ERROR_HANDLE_INVALID;
    glDeleteTextures(static_cast<GLsizei>(it->second.textures.size()), it->second.textures.data());
    runtime->swapchains.erase(it);
    return XR_SUCCESS;
}

XrResult XRAPI_CALL enumerateSwapchainImages(XrSwapchain swapchain, std::uint32_t capacity, std::uint32_t* count, XrSwapchainImageBaseHeader* images) {
    if (!runtime) return XR_ERROR_HANDLE_INVALID;
    auto it = runtime->swapchains.find(idOf(swapchain));
    if (it == runtime->swapchains.end()) return XR_ERROR_HANDLE_INVALID;
    auto* gl = reinterpret_cast<XrSwapchainImageOpenGLKHR*>(images);
    if (capacity > 0 && gl && gl[0].type != XR_TYPE_SWAPCHAIN_IMAGE_OPENGL_KHR) return XR_ERROR_VALIDATION_FAILURE;
    return fill(capacity, count, gl, it->second.textures.size(), [&](XrSwapchainImageOpenGLKHR& image, std::size_t i) {
        image.image = it->second.textures[i];
    });
}

XrResult XRAPI_CALL acquireSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageAcquireInfo*, std::uint32_t* index) {
    if (!runtime) return XR_ERROR_HANDLE_INVALID;
    auto it = runtime->swapchains.find(idOf(swapchain));
    if (it == runtime->swapchains.end()) return XR_ERROR_HANDLE_INVALID;
    Swapchain& sc = it->second;
    if (sc.acquired.size() >= sc.textures.size()) return XR_ERROR_CALL_ORDER_INVALID;
    *index = sc.next;
    sc.acquired.push_back(sc.next);
    sc.next = (sc.next + 1) % static_cast<std::uint32_t>(sc.textures.size());
    return XR_SUCCESS;
}

XrResult XRAPI_CALL waitSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageWaitInfo*) {
    if (!runtime) return XR_ERROR_HANDLE_INVALID;
    auto it = runtime->swapchains.find(idOf(swapchain));
    if (it == runtime->swapchains.end()) return XR_ERROR_HANDLE_INVALID;
    if (it->second.acquired.empty() || it->second.waited) return XR_ERROR_CALL_ORDER_INVALID;
    it->second.waited = true;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL releaseSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageReleaseInfo*) {
    if (!runtime) return XR_ERROR_HANDLE_INVALID;
    auto it = runtime->swapchains.find(idOf(swapchain));
    if (it == runtime->swapchains.end()) return XR_ERROR_HANDLE_INVALID;
    Swapchain& sc = it->second;
    if (!sc.waited) return XR_ERROR_CALL_ORDER_INVALID;
    sc.lastReleased = static_cast<int>(sc.acquired.front());
    sc.acquired.pop_front();
    sc.waited = false;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL waitFrame(XrSession session, const XrFrameWaitInfo*, XrFrameState* state) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    if (!runtime->running) return XR_ERROR_SESSION_NOT_RUNNING;
    Runtime& r = *runtime;
    // The first xrWaitFrame synchronises the application's loop with the display (spec 9.3).
    if (r.waited == 0 && !r.exitRequested) {
        r.queueState(XR_SESSION_STATE_SYNCHRONIZED);
        r.queueState(XR_SESSION_STATE_VISIBLE);
        r.queueState(XR_SESSION_STATE_FOCUSED);
    }
    state->predictedDisplayTime = kFirstDisplayTime + r.waited * kDisplayPeriod;
    state->predictedDisplayPeriod = kDisplayPeriod;
    state->shouldRender = (r.state == XR_SESSION_STATE_VISIBLE || r.state == XR_SESSION_STATE_FOCUSED) ? XR_TRUE : XR_FALSE;
    if (state->shouldRender && r.firstRenderTime < 0) r.firstRenderTime = state->predictedDisplayTime;
    r.lastWaitedTime = state->predictedDisplayTime;
    ++r.waited;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL beginFrame(XrSession session, const XrFrameBeginInfo*) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    if (!runtime->running) return XR_ERROR_SESSION_NOT_RUNNING;
    if (runtime->waited == 0) return XR_ERROR_CALL_ORDER_INVALID;
    bool discarded = runtime->begun >= 0;
    runtime->begun = runtime->waited - 1;
    return discarded ? XR_FRAME_DISCARDED : XR_SUCCESS;
}

XrResult XRAPI_CALL endFrame(XrSession session, const XrFrameEndInfo* info) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    if (!runtime->running) return XR_ERROR_SESSION_NOT_RUNNING;
    if (runtime->begun < 0) return XR_ERROR_CALL_ORDER_INVALID;
    runtime->begun = -1;
    if (info->environmentBlendMode != XR_ENVIRONMENT_BLEND_MODE_OPAQUE) return XR_ERROR_ENVIRONMENT_BLEND_MODE_UNSUPPORTED;
    if (info->displayTime <= 0) return XR_ERROR_TIME_INVALID;
    for (std::uint32_t i = 0; i < info->layerCount; ++i) {
        if (info->layers[i]->type != XR_TYPE_COMPOSITION_LAYER_PROJECTION) return XR_ERROR_LAYER_INVALID;
        const auto* projection = reinterpret_cast<const XrCompositionLayerProjection*>(info->layers[i]);
        if (projection->viewCount != 2) return XR_ERROR_VALIDATION_FAILURE;
        for (std::uint32_t v = 0; v < 2; ++v) {
            const XrSwapchainSubImage& sub = projection->views[v].subImage;
            auto sc = runtime->swapchains.find(idOf(sub.swapchain));
            if (sc == runtime->swapchains.end()) return XR_ERROR_HANDLE_INVALID;
            if (sc->second.lastReleased < 0) return XR_ERROR_LAYER_INVALID;
            const XrRect2Di& r = sub.imageRect;
            if (r.offset.x < 0 || r.offset.y < 0 || r.extent.width <= 0 || r.extent.height <= 0 ||
                static_cast<std::uint32_t>(r.offset.x + r.extent.width) > sc->second.width ||
                static_cast<std::uint32_t>(r.offset.y + r.extent.height) > sc->second.height)
                return XR_ERROR_SWAPCHAIN_RECT_INVALID;
        }
        runtime->capture(*projection, info->displayTime);
    }
    return XR_SUCCESS;
}

XrResult XRAPI_CALL stringToPath(XrInstance instance, const char* text, XrPath* path) {
    if (!isInstance(instance)) return XR_ERROR_HANDLE_INVALID;
    std::string s(text);
    if (s.empty() || s[0] != '/' || s.back() == '/') return XR_ERROR_PATH_FORMAT_INVALID;
    auto& paths = runtime->paths;
    auto it = std::find(paths.begin(), paths.end(), s);
    if (it == paths.end()) it = paths.insert(paths.end(), s);
    *path = static_cast<XrPath>(it - paths.begin() + 1);
    return XR_SUCCESS;
}

XrResult XRAPI_CALL pathToString(XrInstance instance, XrPath path, std::uint32_t capacity, std::uint32_t* count, char* buffer) {
    if (!isInstance(instance)) return XR_ERROR_HANDLE_INVALID;
    if (path == XR_NULL_PATH || path > runtime->paths.size()) return XR_ERROR_PATH_INVALID;
    const std::string& s = runtime->pathString(path);
    return fill(capacity, count, buffer, s.size() + 1, [&](char& c, std::size_t i) { c = i < s.size() ? s[i] : '\0'; });
}

XrResult XRAPI_CALL createActionSet(XrInstance instance, const XrActionSetCreateInfo* info, XrActionSet* set) {
    if (!isInstance(instance)) return XR_ERROR_HANDLE_INVALID;
    std::uint64_t id = runtime->handle();
    runtime->actionSets[id] = info->actionSetName;
    *set = asHandle<XrActionSet_T>(id);
    return XR_SUCCESS;
}

XrResult XRAPI_CALL destroyActionSet(XrActionSet set) {
    if (!runtime || !runtime->actionSets.erase(idOf(set))) return XR_ERROR_HANDLE_INVALID;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL createAction(XrActionSet set, const XrActionCreateInfo* info, XrAction* action) {
    if (!runtime || !runtime->actionSets.count(idOf(set))) return XR_ERROR_HANDLE_INVALID;
    if (runtime->attached) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
    Action a;
    a.name = info->actionName;
    a.type = info->actionType;
    a.subactionPaths.assign(info->subactionPaths, info->subactionPaths + info->countSubactionPaths);
    a.set = set;
    std::uint64_t id = runtime->handle();
    runtime->actions[id] = a;
    *action = asHandle<XrAction_T>(id);
    return XR_SUCCESS;
}

XrResult XRAPI_CALL destroyAction(XrAction action) {
    if (!runtime || !runtime->actions.erase(idOf(action))) return XR_ERROR_HANDLE_INVALID;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL suggestInteractionProfileBindings(XrInstance instance, const XrInteractionProfileSuggestedBinding* suggested) {
    if (!isInstance(instance)) return XR_ERROR_HANDLE_INVALID;
    if (runtime->attached) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
    const std::string& profile = runtime->pathString(suggested->interactionProfile);
    if (profile.rfind("/interaction_profiles/", 0) != 0) return XR_ERROR_PATH_UNSUPPORTED;
    auto& list = runtime->suggested[suggested->interactionProfile];
    list.clear();   // a later suggestion for a profile replaces the earlier one
    for (std::uint32_t i = 0; i < suggested->countSuggestedBindings; ++i) {
        const XrActionSuggestedBinding& b = suggested->suggestedBindings[i];
        if (!runtime->actions.count(idOf(b.action))) return XR_ERROR_HANDLE_INVALID;
        const std::string& path = runtime->pathString(b.binding);
        if (runtime->handOf(b.binding) < 0 || path.find("/input/") == std::string::npos) return XR_ERROR_PATH_UNSUPPORTED;
        list.push_back({b.action, b.binding});
    }
    runtime->note("bindings suggested for " + profile + ": " + std::to_string(list.size()));
    return XR_SUCCESS;
}

XrResult XRAPI_CALL attachSessionActionSets(XrSession session, const XrSessionActionSetsAttachInfo* info) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    if (runtime->attached) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
    for (std::uint32_t i = 0; i < info->countActionSets; ++i)
        if (!runtime->actionSets.count(idOf(info->actionSets[i]))) return XR_ERROR_HANDLE_INVALID;
    runtime->attached = true;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL getCurrentInteractionProfile(XrSession session, XrPath topLevelUserPath, XrInteractionProfileState* state) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    if (!runtime->attached) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
    state->interactionProfile = XR_NULL_PATH;
    if (runtime->handOf(topLevelUserPath) < 0) return XR_ERROR_PATH_UNSUPPORTED;
    auto& paths = runtime->paths;
    auto it = std::find(paths.begin(), paths.end(), runtime->script.interactionProfile);
    if (runtime->profileAnnounced && it != paths.end() && runtime->suggested.count(static_cast<XrPath>(it - paths.begin() + 1)))
        state->interactionProfile = static_cast<XrPath>(it - paths.begin() + 1);
    return XR_SUCCESS;
}

XrResult XRAPI_CALL syncActions(XrSession session, const XrActionsSyncInfo* info) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    if (!runtime->attached) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
    (void)info;
    if (runtime->state != XR_SESSION_STATE_FOCUSED) {
        for (auto& [key, v] : runtime->synced) v = SyncedValue{};
        return XR_SESSION_NOT_FOCUSED;
    }
    if (!runtime->profileAnnounced) {   // the controllers "appear" at the first focused sync (spec 11.4)
        runtime->profileAnnounced = true;
        XrEventDataBuffer buffer{};
        auto* e = reinterpret_cast<XrEventDataInteractionProfileChanged*>(&buffer);
        e->type = XR_TYPE_EVENT_DATA_INTERACTION_PROFILE_CHANGED;
        e->session = runtime->sessionHandle;
        runtime->events.push_back(buffer);
    }
    runtime->sync();
    return XR_SUCCESS;
}

// The synced value of an action for a subaction path (XR_NULL_PATH: both hands).
XrResult syncedValue(XrSession session, const XrActionStateGetInfo* info, XrActionType type, SyncedValue& value) {
    if (!isSession(session)) return XR_ERROR_HANDLE_INVALID;
    auto a = runtime->actions.find(idOf(info->action));
    if (a == runtime->actions.end()) return XR_ERROR_HANDLE_INVALID;
    if (!runtime->attached) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
    if (a->second.type != type) return XR_ERROR_ACTION_TYPE_MISMATCH;
    int hand = runtime->handOf(info->subactionPath);
    if (info->subactionPath != XR_NULL_PATH &&
        std::find(a->second.subactionPaths.begin(), a->second.subactionPaths.end(), info->subactionPath) == a->second.subactionPaths.end())
        return XR_ERROR_PATH_UNSUPPORTED;
    auto it = runtime->synced.find({idOf(info->action), hand});
    value = it == runtime->synced.end() ? SyncedValue{} : it->second;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL getActionStateBoolean(XrSession session, const XrActionStateGetInfo* info, XrActionStateBoolean* state) {
    SyncedValue v;
    if (XrResult r = syncedValue(session, info, XR_ACTION_TYPE_BOOLEAN_INPUT, v); r != XR_SUCCESS) return r;
    state->currentState = v.value > 0.5f ? XR_TRUE : XR_FALSE;
    state->changedSinceLastSync = v.changed ? XR_TRUE : XR_FALSE;
    state->lastChangeTime = v.lastChange;
    state->isActive = v.active ? XR_TRUE : XR_FALSE;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL getActionStateFloat(XrSession session, const XrActionStateGetInfo* info, XrActionStateFloat* state) {
    SyncedValue v;
    if (XrResult r = syncedValue(session, info, XR_ACTION_TYPE_FLOAT_INPUT, v); r != XR_SUCCESS) return r;
    state->currentState = v.value;
    state->changedSinceLastSync = v.changed ? XR_TRUE : XR_FALSE;
    state->lastChangeTime = v.lastChange;
    state->isActive = v.active ? XR_TRUE : XR_FALSE;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL getActionStateVector2f(XrSession session, const XrActionStateGetInfo* info, XrActionStateVector2f* state) {
    SyncedValue v;
    if (XrResult r = syncedValue(session, info, XR_ACTION_TYPE_VECTOR2F_INPUT, v); r != XR_SUCCESS) return r;
    state->currentState = {v.vector.x, v.vector.y};
    state->changedSinceLastSync = v.changed ? XR_TRUE : XR_FALSE;
    state->lastChangeTime = v.lastChange;
    state->isActive = v.active ? XR_TRUE : XR_FALSE;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL getActionStatePose(XrSession session, const XrActionStateGetInfo* info, XrActionStatePose* state) {
    SyncedValue v;
    if (XrResult r = syncedValue(session, info, XR_ACTION_TYPE_POSE_INPUT, v); r != XR_SUCCESS) return r;
    state->isActive = v.active ? XR_TRUE : XR_FALSE;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL applyHapticFeedback(XrSession session, const XrHapticActionInfo*, const XrHapticBaseHeader*) {
    return isSession(session) ? XR_SUCCESS : XR_ERROR_HANDLE_INVALID;
}
XrResult XRAPI_CALL stopHapticFeedback(XrSession session, const XrHapticActionInfo*) {
    return isSession(session) ? XR_SUCCESS : XR_ERROR_HANDLE_INVALID;
}

XrResult XRAPI_CALL getInstanceProcAddr(XrInstance instance, const char* name, PFN_xrVoidFunction* function);

struct Entry {
    const char* name;
    PFN_xrVoidFunction function;
    bool withoutInstance;   // may be asked for with XR_NULL_HANDLE (OpenXR 3.2)
};
#define CURETTE_ENTRY(name, fn, noInstance) {name, reinterpret_cast<PFN_xrVoidFunction>(fn), noInstance}
const Entry kEntries[] = {
    CURETTE_ENTRY("xrGetInstanceProcAddr", getInstanceProcAddr, true),
    CURETTE_ENTRY("xrEnumerateInstanceExtensionProperties", enumerateInstanceExtensionProperties, true),
    CURETTE_ENTRY("xrCreateInstance", createInstance, true),
    CURETTE_ENTRY("xrDestroyInstance", destroyInstance, false),
    CURETTE_ENTRY("xrGetInstanceProperties", getInstanceProperties, false),
    CURETTE_ENTRY("xrPollEvent", pollEvent, false),
    CURETTE_ENTRY("xrResultToString", resultToString, false),
    CURETTE_ENTRY("xrStructureTypeToString", structureTypeToString, false),
    CURETTE_ENTRY("xrGetSystem", getSystem, false),
    CURETTE_ENTRY("xrGetSystemProperties", getSystemProperties, false),
    CURETTE_ENTRY("xrEnumerateViewConfigurations", enumerateViewConfigurations, false),
    CURETTE_ENTRY("xrGetViewConfigurationProperties", getViewConfigurationProperties, false),
    CURETTE_ENTRY("xrEnumerateViewConfigurationViews", enumerateViewConfigurationViews, false),
    CURETTE_ENTRY("xrEnumerateEnvironmentBlendModes", enumerateEnvironmentBlendModes, false),
    CURETTE_ENTRY("xrGetOpenGLGraphicsRequirementsKHR", getOpenGLGraphicsRequirements, false),
    CURETTE_ENTRY("xrCreateSession", createSession, false),
    CURETTE_ENTRY("xrDestroySession", destroySession, false),
    CURETTE_ENTRY("xrBeginSession", beginSession, false),
    CURETTE_ENTRY("xrEndSession", endSession, false),
    CURETTE_ENTRY("xrRequestExitSession", requestExitSession, false),
    CURETTE_ENTRY("xrEnumerateReferenceSpaces", enumerateReferenceSpaces, false),
    CURETTE_ENTRY("xrCreateReferenceSpace", createReferenceSpace, false),
    CURETTE_ENTRY("xrGetReferenceSpaceBoundsRect", getReferenceSpaceBoundsRect, false),
    CURETTE_ENTRY("xrCreateActionSpace", createActionSpace, false),
    CURETTE_ENTRY("xrLocateSpace", locateSpace, false),
    CURETTE_ENTRY("xrDestroySpace", destroySpace, false),
    CURETTE_ENTRY("xrLocateViews", locateViews, false),
    CURETTE_ENTRY("xrEnumerateSwapchainFormats", enumerateSwapchainFormats, false),
    CURETTE_ENTRY("xrCreateSwapchain", createSwapchain, false),
    CURETTE_ENTRY("xrDestroySwapchain", destroySwapchain, false),
    CURETTE_ENTRY("xrEnumerateSwapchainImages", enumerateSwapchainImages, false),
    CURETTE_ENTRY("xrAcquireSwapchainImage", acquireSwapchainImage, false),
    CURETTE_ENTRY("xrWaitSwapchainImage", waitSwapchainImage, false),
    CURETTE_ENTRY("xrReleaseSwapchainImage", releaseSwapchainImage, false),
    CURETTE_ENTRY("xrWaitFrame", waitFrame, false),
    CURETTE_ENTRY("xrBeginFrame", beginFrame, false),
    CURETTE_ENTRY("xrEndFrame", endFrame, false),
    CURETTE_ENTRY("xrStringToPath", stringToPath, false),
    CURETTE_ENTRY("xrPathToString", pathToString, false),
    CURETTE_ENTRY("xrCreateActionSet", createActionSet, false),
    CURETTE_ENTRY("xrDestroyActionSet", destroyActionSet, false),
    CURETTE_ENTRY("xrCreateAction", createAction, false),
    CURETTE_ENTRY("xrDestroyAction", destroyAction, false),
    CURETTE_ENTRY("xrSuggestInteractionProfileBindings", suggestInteractionProfileBindings, false),
    CURETTE_ENTRY("xrAttachSessionActionSets", attachSessionActionSets, false),
    CURETTE_ENTRY("xrGetCurrentInteractionProfile", getCurrentInteractionProfile, false),
    CURETTE_ENTRY("xrSyncActions", syncActions, false),
    CURETTE_ENTRY("xrGetActionStateBoolean", getActionStateBoolean, false),
    CURETTE_ENTRY("xrGetActionStateFloat", getActionStateFloat, false),
    CURETTE_ENTRY("xrGetActionStateVector2f", getActionStateVector2f, false),
    CURETTE_ENTRY("xrGetActionStatePose", getActionStatePose, false),
    CURETTE_ENTRY("xrApplyHapticFeedback", applyHapticFeedback, false),
    CURETTE_ENTRY("xrStopHapticFeedback", stopHapticFeedback, false),
};
#undef CURETTE_ENTRY

XrResult XRAPI_CALL getInstanceProcAddr(XrInstance instance, const char* name, PFN_xrVoidFunction* function) {
    if (!name || !function) return XR_ERROR_VALIDATION_FAILURE;
    *function = nullptr;
    if (instance != XR_NULL_HANDLE && !isInstance(instance)) return XR_ERROR_HANDLE_INVALID;
    for (const Entry& e : kEntries) {
        if (std::strcmp(e.name, name) != 0) continue;
        if (instance == XR_NULL_HANDLE && !e.withoutInstance) return XR_ERROR_HANDLE_INVALID;
        *function = e.function;
        return XR_SUCCESS;
    }
    return XR_ERROR_FUNCTION_UNSUPPORTED;
}

}  // namespace
}  // namespace curette::xr_test

extern "C" __attribute__((visibility("default"))) XrResult XRAPI_CALL xrNegotiateLoaderRuntimeInterface(const XrNegotiateLoaderInfo* loaderInfo,
                                                                                                      XrNegotiateRuntimeRequest* request) {
    if (!loaderInfo || !request || loaderInfo->structType != XR_LOADER_INTERFACE_STRUCT_LOADER_INFO ||
        loaderInfo->structVersion != kLoaderInfoStructVersion || loaderInfo->structSize != sizeof(XrNegotiateLoaderInfo) ||
        request->structType != XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST || request->structVersion != kRuntimeInfoStructVersion ||
        request->structSize != sizeof(XrNegotiateRuntimeRequest))
        return XR_ERROR_INITIALIZATION_FAILED;
    if (loaderInfo->minInterfaceVersion > kLoaderRuntimeVersion || loaderInfo->maxInterfaceVersion < kLoaderRuntimeVersion)
        return XR_ERROR_INITIALIZATION_FAILED;
    if (XR_VERSION_MAJOR(loaderInfo->minApiVersion) > 1 || XR_VERSION_MAJOR(loaderInfo->maxApiVersion) < 1) return XR_ERROR_INITIALIZATION_FAILED;
    request->runtimeInterfaceVersion = kLoaderRuntimeVersion;
    request->runtimeApiVersion = XR_CURRENT_API_VERSION;
    request->getInstanceProcAddr = curette::xr_test::getInstanceProcAddr;
    return XR_SUCCESS;
}
