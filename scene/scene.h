#pragma once
// The scene file (JSON): what to load and how to look at it. Everything a scene needs is named here, so a
// scene allocates and computes only what it uses. Relative paths are relative to the scene file.
//
// {
//   "volume": {"path": "/usr/share/mricron/templates/ch2.nii.gz" | a DICOM folder or file,
//              "format": "auto" | "nifti" | "nrrd" | "raw" | "metaimage" | "dicom",
//              "index": 0 (4-D/5-D files: which volume), "series": number | "UID" (DICOM),
//              "raw": {"dims": [x,y,z], "type": "uint8|int16|uint16|int32|float32|float64",
//                      "endian": "little|big", "spacing": [..], "origin": [..], "header_bytes": 0,
//                      "gzip": false}},                                  (raw only)
//   "transfer_function": "tf.json" | "tf.vp" | { inline TF, see assets/tf/README.md },
//   "camera": {"target": "center" | [x,y,z], "distance_mm": "fit" | number, "azimuth_deg": 0,
//              "elevation_deg": 0, "fov_deg": 30, "near_mm", "far_mm" (default: from the distance and the
//              volume's bounding radius; a saved scene writes them, session/plan_scene.h)},
//   "shading": "solid" | "phong" | "lao" | "cao" | "dos" | "ismos",
//   "lights": [{"direction": [x,y,z], "color": [r,g,b], "intensity": 1, "space": "camera" | "world"}],
//   "image": {"width": 512, "height": 512, "background": [r,g,b,a]},
//   "raycast": {"step_mm": 0 (auto), "early_termination": 0.99, "jitter_seed": 0, "skip_empty_space": true,
//               "cut_faces": {"enabled": true, "normal_depth_mm": 10.0, "normal_opacity": 0.9}},
//   "ambient_occlusion": {"rays": "26" | "6" | "14" | "54" | "fibonacci:K", "samples": 20, "step_mm": 1.0,
//                         "antialiasing_samples": 32, "jitter": 0.025, "weights": "uniform" | "sky",
//                         "ambient_scale": 2.0, "dispatch": "compacted" | "full_grid"},
//   "clip_meshes": [{"name": "probe", "mesh": {see mesh/mesh_description.h}, "position_mm": [x,y,z],
//                    "rotation_deg": [about x, about y, about z] (applied x, then y, then z),
//                    "scale": 1.0 | [sx,sy,sz], "clips_tubes": false}]       (at most 16)
//   "clip_mesh_display": {"show": true | false (default: off in `render` and exports, on in the viewer),
//                         "opacity": 0.22 (the meshes' translucent fill), "outline_opacity": 0.9 (their
//                         silhouettes and creases)}   (drawn over the image, never into it: render/clip_mesh_overlay.h)
//   "tubes": [{"path": "AF_L.trk" | "x.tck" | "x.trk.gz" | "x.tck.gz" | "x.trx" (zip or folder), "radius_mm": 0.5, "sides": 8, "caps": true,
//              "smoothing": "catmull-rom" | "none", "step_mm": 0.5,
//              "color": "direction" | "scalar" | [r,g,b], "scalar": "FA", "scalar_range": [lo, hi]}],
//   "tube_rendering": {"mode": "tubes" | "lines", "build": "cpu" | "gpu" | "impostor", "geometry_opacity": 0.9, "vicinity_distance_mm": 3,
//                      "vicinity_samples": 64, "depth_bias_mm": 0.5, "line_diffuse_exponent": 2,
//                      "material": {"ambient": .25, "diffuse": .75, "specular": .35, "specular_power": 32}},
//   "dos": {"cone_angle_deg": 60, "grid": 3, "slice_distance_mm": 0 (auto), "ambient": 1.0},
//   "ismos": {"occlusion": "partial" | "full", "opacity": "exact" | "fit", "layers": 4, "blend_layers": true,
//             "light_samples": 16, "test_points": 32, "hemisphere_radius": 2.0, "disk_radius": 0.2,
//             "ambient": 0.3, "opacity_threshold": 0.5, "depth_bias": 0.01, "falloff": false,
//             "light_positions": "hemisphere" | "sphere", "base": "phong" | "solid"}   (render/model/frame.h)
//   lights also take "disk_radius": d (ISMOS, texture units) and "spot": {"angle_deg": 20,
//             "target": [x,y,z] world mm (default: the volume's centre)},
//   "labels": [{"path": "aal.nii.gz" (an integer volume on its own grid), "name": "AAL" (default: file stem),
//               "table": "aal.nii.txt" (names and colours, io/label_table.h; default: the sibling
//                        X.nii.txt, X.txt or X.ctbl when one exists), "colors": "aal.nii.lut" (overrides colours),
//               "opacity": 0.5 (per unit length when shown), "show": "all" | "protected" | "none" | [ids or names],
//               "protected": [ids or names], "protected_color": [r, g, b] (default: the table's colours)}],
//                                                                       (at most 8 sets)
//   "removal": "plan.removal.nii.gz" (the drilled removal on the scan grid, session/removal_file.h; a saved scene
//              writes it beside itself),
//   "report": {"tissue": "opacity" | "labels" | "all", "opacity_threshold": 0.02,
//              "tissue_labels": [ids or names of the first label set] (default: all its labels), "tract_step_mm": 0.25}
// }
// Tube entries also take "name" (default: file stem) and "protected": true (the report's margins and warnings).

#include "io/volume_file.h"
#include "scene/scene_keys.h"
#include "mesh/rigid_pose.h"
#include "mesh/triangle_mesh.h"
#include "render/model/lao_settings.h"
#include "render/model/tube_geometry.h"
#include "render/model/frame.h"
#include "base/transfer_function.h"
#include "render/model/volume_geometry.h"

#include <filesystem>
#include <memory>
#include <optional>

namespace curette {

struct CameraSpec {
    std::optional<glm::dvec3> target;        // nullopt: the volume's centre
    std::optional<double> distanceMm;        // nullopt: fit the volume in view
    double azimuthDeg = 0, elevationDeg = 0, fovYDeg = 30;
    std::optional<double> nearMm, farMm;     // nullopt: from the distance and the volume (OrbitCamera::fit)
};

// A label volume beside the scan. Ids and names are resolved against the table when the scene is loaded
// (scene/scene_labels.h), so the scene keeps what the user wrote.
struct SceneLabels {
    std::string name;
    std::filesystem::path path;
    std::optional<std::filesystem::path> table, colors;
    double opacity = 0.5;
    enum class Show { All, Protected, None, Listed } show = Show::All;
    std::vector<std::string> shown;       // Show::Listed: ids or names
    std::vector<std::string> protectedLabels;
    std::optional<glm::dvec3> protectedColor;
    std::string jsonPath;                 // "labels[0]", for messages
};

// What the removal report counts as tissue (plan/removal_report.h): by default the voxels the TF makes
// visible (opacity per unit length above a threshold), which is what the planner sees removed.
struct ReportSpec {
    enum class Tissue { Opacity, Labels, All } tissue = Tissue::Opacity;
    double opacityThreshold = 0.02;
    std::vector<std::string> tissueLabels;   // Tissue::Labels: ids or names of the first label set (empty: all)
    double tractStepMm = 0.25;
};

struct Scene {
    std::filesystem::path file;
    nlohmann::json json;                     // the file as parsed (the scene writer and the panels start from it)
    std::filesystem::path volumePath;
    io::VolumeReadOptions volumeOptions;
    TransferFunction transferFunction;
    std::string transferFunctionSource;      // file path, or "<scene file>: transfer_function"
    CameraSpec camera;
    ShadingMode shading = ShadingMode::Phong;
    std::vector<Light> lights{Light{}};
    glm::ivec2 imageSize{512, 512};
    glm::dvec4 background{0, 0, 0, 1};
    RaycastSettings raycast;
    LaoSettings lao;
    std::vector<SceneClipMesh> clipMeshes;
    ClipMeshDisplaySpec clipMeshDisplay;
    std::vector<SceneTubes> tubes;
    bool tubesAsLines = false;
    TubeBuild tubeBuild = TubeBuild::Cpu;    // where tube geometry is made (tubes mode; scene_keys.h)
    TubeShading tubeShading;
    DosSettings dos;
    IsmosSettings ismos;
    std::vector<SceneLabels> labels;
    ReportSpec report;
    std::optional<std::filesystem::path> removalPath;   // "removal", resolved against the scene's folder
};

// A file's name with the known volume and tract suffixes taken off one at a time, the full name first:
// "aal.nii.gz" -> {"aal.nii.gz", "aal.nii", "aal"}. The last is what the file is called in a report; the
// others are where its sibling files are looked for (scene/scene_labels.h).
std::vector<std::string> fileNameStems(const std::filesystem::path& path);

// Reads and validates a scene file (and the TF file it names); throws InputError naming the key.
Scene loadScene(const std::filesystem::path& path);
Scene parseScene(std::string_view text, const std::filesystem::path& path);

// The camera the scene asks for, resolved against the loaded volume ("center", "fit").
OrbitCamera resolveCamera(const CameraSpec& spec, const VolumeGeometry& geometry);

// The first frame of the scene: resolved camera, image size, shading, lights, ray settings.
FrameDescription initialFrame(const Scene& scene, const VolumeGeometry& geometry);

}  // namespace curette
