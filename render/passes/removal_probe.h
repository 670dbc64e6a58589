#pragma once
// The GPU side of the removal report (plan/removal_report.h): under the clip meshes' current poses, how much
// of each voxel the meshes cover (shaders/removal_count.comp, the sample pattern of step IV through
// shaders/clip_coverage.glsl, so the report and the rendered carve agree voxel by voxel), and which of a list
// of world points lie inside a mesh (shaders/clip_probe.comp, the renderer's own clip test: the tract points
// a carve cuts). The CPU twins are plan::removalFieldCpu and plan::insideFlagsCpu.

#include "render/passes/clip_mesh_set.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "plan/removal_field.h"
#include "render/mesh_voxel_box.h"
#include "render/model/volume_geometry.h"

#include <cstdint>
#include <vector>

namespace curette {

class RemovalProbe {
public:
    // antiAliasingSamples: N of step IV (the scene's ambient_occlusion.antialiasing_samples).
    RemovalProbe(const VolumeGeometry& geometry, int antiAliasingSamples);

    // The removal field over voxelBoxAroundMeshes (an empty field without meshes). Updates the meshes' maps first.
    plan::RemovalField removalField(clip::ClipMeshSet& clip);
    // Per point, 1 when inside some clip mesh (every mesh, whether or not it clips tubes: the carve cuts them).
    std::vector<std::uint8_t> insideFlags(clip::ClipMeshSet& clip, const std::vector<glm::dvec3>& points);

private:
    VolumeGeometry geometry_;
    int antiAliasingSamples_;
    gl::Buffer antiAliasing_;
    gl::Program countProgram_, probeProgram_;
};

}  // namespace curette
