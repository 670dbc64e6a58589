#pragma once
// Sessions: JSON Lines, written atomically. Line 1 is the header (format, version, scene, devices, mapping,
// and the state at the start: shading, meshes, input pipeline, so a recording may start mid-run); every further line is one frame: time, dt, image size, camera, shading, every clip
// mesh's pose, the keyboard/mouse state, the devices and meshes that appeared or went, the panels' setting
// edits (version 3, scene/setting_edit.h), the mesh panel's hold requests (version 4), the drilling applied
// (version 5; from version 6 derived from the keys and devices, and the header names the removal at the start),
// the head, eyes and controllers of a head-mounted display (version 6: `view --xr`; 7: the controllers' volume
// and erase buttons and the volume's place in the room), the edits an undo or redo of a setting edit applied
// (version 7, "history_edits"), and the raw HID reports
// received since the previous frame (hex). Poses are written with 17 significant digits, so they read back to
// the same doubles.

#include "scene/setting_edit.h"
#include "mesh/rigid_pose.h"
#include "input/pipeline.h"
#include "render/model/camera.h"
#include "render/model/shading_mode.h"
#include "render/model/tracked_view.h"

#include <glm/gtc/quaternion.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace curette {

inline constexpr int kSessionVersion = 8;   // 3: setting edits (scene/setting_edit.h); 4: hold requests, lights added and removed;
                                            // 5: drilling and its undo/redo; 6: drilling from keys and devices (actions, so
                                            // --from-reports re-derives it; 64-bit keys), the removal at the start,
                                            // head-mounted display sessions; 7: the controllers' volume and erase
                                            // buttons, the volume's place in the room, undo/redo of setting edits
                                            // too ("history_edits"); 8: two hands scale the volume (the
                                            // anchor's "volume_scale")
// The first version whose controllers move the volume, erase and undo/redo (session/xr_hands.h).
inline constexpr int kXrVolumeVersion = 7;
// The first version whose two hands holding the volume scale it (session/xr_hands.h); before, the first hand carries it.
inline constexpr int kXrTwoHandVersion = 8;
// The first version whose drilling comes from the recorded keys and devices: replay --from-reports re-derives
// it and compares it with the frame's "drill"/"drill_history"; before, those are the input.
inline constexpr int kDrillFromInputVersion = 6;
// The first version whose undo history holds setting edits as well as strokes (the edits an undo or redo
// applied are the frame's "history_edits").
inline constexpr int kUndoEditsVersion = 7;
inline constexpr int kOldestSessionVersion = 1;

struct SessionDevice {
    int id = 0;
    std::string family, path, product, bus;
    int vendorId = 0, productId = 0;
};

struct SessionReport {
    int device = 0;
    double time = 0;
    std::vector<std::uint8_t> bytes;
};

struct SessionMesh {
    int id = 0;
    glm::dvec3 position{0.0};
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};
    glm::dvec3 scale{1.0};
};

struct SessionLight {
    glm::dvec3 direction{0.0, 0.0, 1.0};   // towards the light; camera space (right, up, towards the viewer) or world
    bool cameraSpace = true;
};

// A mesh drilling in a frame (version 5; session/drilling.h): it removes (erase: restores) what it sweeps
// from its pose before the frame to its pose after.
struct SessionDrill {
    int mesh = 0;   // id
    bool erase = false;
    bool operator==(const SessionDrill&) const = default;
};
enum class HistoryCommand { Undo, Redo };   // of the last stroke or setting edit (only strokes before version 7)

// A head-mounted display session (version 6, `view --xr`): the room space the runtime located everything in
// (the volume's anchor follows from it: render/model/tracked_view.h) and each eye's recommended image size.
struct SessionXr {
    RoomSpace space = RoomSpace::Stage;
    std::array<glm::ivec2, 2> recommendedSize{};   // left, right
    std::string runtime, system;                   // as the runtime named them (information only)
};

// One controller after the frame's action sync, in the room space (metres). Untracked: its pose is not
// recorded (nothing reads it). The inputs are the action states the hand's actions come from
// (session/xr_hands.h), so a replay can derive them again.
struct SessionXrHand {
    bool tracked = false;
    TrackedView grip;                 // position and orientation (fov unused)
    double squeeze = 0.0, trigger = 0.0;
    glm::dvec2 thumbstick{0.0};
    bool shadingPressed = false;      // the shading button went down at this sync
    bool moveVolume = false, erase = false;   // held (version 7)
    bool operator==(const SessionXrHand&) const = default;
};

// A frame of a head-mounted display: when the runtime displays it, the head and both eyes as located
// (absent: not located, or the frame was not rendered), and both hands.
struct SessionXrFrame {
    std::int64_t displayTimeNs = 0;
    std::optional<TrackedView> head;                  // the view space in the room (fov unused)
    std::optional<std::array<TrackedView, 2>> views;  // left, right: pose and asymmetric field of view
    std::array<SessionXrHand, 2> hands{};             // left, right
    // The volume's place in the room after the frame's hands (version 7; absent: on its table). Its world
    // centre is the volume's own and is not recorded.
    std::optional<RoomAnchor> anchor;
};

struct SessionAddedMesh {
    int id = 0;
    std::string name;
    std::string description;  // the mesh as a scene describes it (JSON)
};

struct SessionFrame {
    std::size_t index = 0;
    double time = 0, dt = 0;
    glm::ivec2 size{0};
    OrbitCamera camera;
    ShadingMode shading = ShadingMode::Phong;
    std::vector<SessionMesh> meshes;
    // Every light's direction after the frame's actions and edits (version 2; absent: unchanged); as many as
    // the header's lights and the lights.add/lights.remove edits since make (version 4).
    std::optional<std::vector<glm::dvec3>> lights;
    std::uint64_t keys = 0;          // input::KeyboardMouseState::keys (32 bits before version 6)
    glm::dvec2 drag{0.0};
    glm::dvec2 lightDrag{0.0};   // Shift + left drag (input::KeyboardMouseState::lightDragPixels)
    std::vector<SessionDevice> devicesAdded;
    std::vector<int> devicesRemoved;
    std::vector<SessionAddedMesh> meshesAdded;
    std::vector<int> meshesRemoved;
    std::vector<SettingEdit> edits;   // the frame's panel edits, as applied, after its actions (version 3)
    // The hold requests the frame's input pipeline step applied, before its reports (version 4;
    // input::HoldRequest): {"binding": N | "keyboard", "mesh": index}.
    std::vector<input::HoldRequest> holds;
    // The meshes drilling this frame, then the undo/redo commands applied after them (version 5; "drill" and
    // "drill_history"). From version 6 they are what the frame's actions applied (a record, re-derived from the
    // keys and reports). From version 7 an undo or redo may revert a setting edit: the edits it applied are
    // "history_edits" (a record: replay re-derives them from the undo history and checks them; not in "edits").
    std::vector<SessionDrill> drills;
    std::vector<HistoryCommand> historyCommands;
    std::vector<SettingEdit> historyEdits;
    std::optional<SessionXrFrame> xr;   // version 6, in sessions whose header has "xr"
    std::vector<SessionReport> reports;
};

// A clip mesh present when recording started. Scene meshes have their scene index as id and no description;
// meshes added during the run carry their description (a scene's mesh JSON) so a replay can rebuild them.
struct SessionMeshStart {
    int id = 0;
    std::string name;
    std::string description;
    clip::RigidPose pose, initialPose;   // initialPose: where reset_pose puts it
    glm::dvec3 scale{1.0};
    std::optional<bool> clipsTubes;      // version 3 (before: the scene's, or false for added meshes)
};

struct SessionHeader {
    int version = kSessionVersion;
    std::string scene;            // as given when recording; relative paths are relative to the session file
    std::string created;          // ISO 8601 UTC
    std::vector<SessionDevice> devices;
    std::string mappingJson;      // the mapping in effect (input/mapping.h format), validated on reading
    ShadingMode shading = ShadingMode::Phong;     // at the start
    std::vector<SessionMeshStart> meshes;         // at the start
    int nextMeshId = 0;                           // the id the next added mesh takes
    std::optional<std::vector<SessionLight>> lights;   // at the start (version 2; absent: the scene's)
    int selectedLight = 0;                        // the light MoveLight{-1} turns, at the start
    std::vector<SettingEdit> edits;               // settings edited before the start (version 3; no mesh edits)
    input::InputPipelineState inputState;         // at the start: device states, held meshes, previous buttons
    double keyboardMmPerSecond = 40.0, keyboardDegPerSecond = 60.0;
    // The drilled removal at the start (version 6; session/removal_file.h): a file relative to the session file's
    // folder and its RemovalVolume::digest; empty: nothing drilled (before version 6: the scene's removal).
    std::string removal, removalDigest;
    std::optional<SessionXr> xr;                  // a head-mounted display session (version 6)
};

struct Session {
    std::filesystem::path file;
    SessionHeader header;
    std::vector<SessionFrame> frames;
    std::string warning;          // set when lenient reading dropped a bad tail
};

// The scene a session was recorded on: its header's path, relative to the session file's folder.
std::filesystem::path sessionScenePath(const Session& session);

std::string sessionHeaderLine(const SessionHeader& header);
std::string sessionFrameLine(const SessionFrame& frame);

// Strict: any bad line is an InputError naming "line N" and the key. Lenient: a bad line ends the session
// there (the valid prefix is kept, `warning` says why); a bad header is always an error.
Session readSession(const std::filesystem::path& path, bool lenient);
Session parseSession(std::string_view text, const std::filesystem::path& path, bool lenient);

// Keeps the frames in memory and writes the whole session atomically at every checkpoint (each
// `checkpointSeconds` of session time) and at finish(): a crash loses at most the last interval, and the file
// on disk is always a complete session.
class SessionRecorder {
public:
    SessionRecorder(std::filesystem::path path, SessionHeader header, double checkpointSeconds = 5.0);
    ~SessionRecorder();
    void add(const SessionFrame& frame);
    void finish();
    std::size_t frames() const { return lines_.size(); }
    const std::filesystem::path& path() const { return path_; }

private:
    void write();
    std::filesystem::path path_;
    std::string header_;
    std::vector<std::string> lines_;
    double checkpointSeconds_, lastCheckpoint_ = 0;
    bool finished_ = false;
};

}  // namespace curette
