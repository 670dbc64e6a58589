#pragma once
// The GPU resources a frame can use, in one table of descriptors (name, format, purpose); the owner of each
// reports its size, and the memory report (`curette render --timings`) is derived from the table. Pass
// declarations in render/model/frame_plan.h name their inputs and outputs by these ids.

#include <cstddef>
#include <string>
#include <vector>

namespace curette {

enum class Resource {
    Volume,            // V
    GradientVolume,    // phong's central differences per voxel (8-bit scans: render/gradient_volume.h)
    TransferFunction,  // colour and opacity table
    GradientOpacity,   // gradient-opacity table
    Occupancy,         // empty-space-skipping bricks
    SeenBricks,        // the bricks whose voxels' LAO a visible sample can read (steps I and V)
    LabelVolume,       // label ids on the scan grid and their styles (scenes with labels only)
    DrilledRemoval,    // the drill's removal: drilled fraction per voxel, near-drill flags per brick (once drilled)
    ClipMeshGeometry,  // clip-mesh vertex and index buffers
    ClipMaps,          // steps II-III: depth maps and dilated maps of every mesh
    ClippedOpacity,    // V_o
    CategoryMask,      // V_m
    PrecomputedAo,     // V_PAO
    Ambient,           // V_AO
    RecomputeList,     // step V's compacted list
    VisitedBricks,     // the bricks steps IV and V visit, with step IV's flags per brick
    LaoDirections,     // the K LAO rays
    TubeGeometry,      // tube or line vertex buffers
    GBuffer,           // tube G-buffer and the partial-occlusion buffer
    OcclusionBuffers,  // the slab pass's ping-pong DOS occlusion buffers
    OutputImage,       // the frame's RGBA
    PreviewImage,      // a viewer's preview frames' RGBA (kept apart from the exact frame in slices)
    IsmosLayers,       // ISMOS: layer fronts and opacities (pass 1 -> pass 2)
    IsmosLayerBacks,   // ISMOS: layer backs (exact partial occlusion only)
    IsmosFit,          // ISMOS: beta of the transmittance fit (alpha_app only)
    IsmosLightSamples, // ISMOS: the N samples of every light disk, texture space
    Count
};

struct ResourceInfo {
    Resource id;
    const char* name;      // as the memory report and the plan print it
    const char* format;
    const char* purpose;
    // Its size grows with the volume's voxels: the memory report gives its bytes per voxel.
    bool volumeSized = false;
};

const ResourceInfo& resourceInfo(Resource id);

// One allocated resource and its size; `format` only where the owner knows more than the table (the volume's
// storage type).
struct GpuAllocation {
    Resource resource;
    std::size_t bytes = 0;
    std::string format;     // empty: the table's
    const char* name() const { return resourceInfo(resource).name; }
    std::string formatText() const { return format.empty() ? resourceInfo(resource).format : format; }
};

}  // namespace curette
