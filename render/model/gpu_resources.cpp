#include "render/model/gpu_resources.h"

#include "base/enum_table.h"

namespace curette {

namespace {
constexpr ResourceInfo kResources[] = {
    {Resource::Volume, "V (data volume)", "R8, R16 or R32F 3D", "the scan, in its own storage type", true},
    {Resource::GradientVolume, "gradient volume", "RGBA16_SNORM 3D", "phong's central differences per voxel, one texel of padding (8-bit scans, phong frames)", true},
    {Resource::TransferFunction, "transfer function", "RGBA32F 1D", "colour and opacity per unit length over the value range"},
    {Resource::GradientOpacity, "gradient opacity", "R32F 1D", "opacity factor over the gradient magnitude"},
    {Resource::Occupancy, "occupancy bricks", "R8 3D", "per 8^3 brick: 0 where a sample may be non-transparent, else the Chebyshev distance (bricks) to the nearest such brick", true},
    {Resource::SeenBricks, "seen bricks", "R8 3D", "per 4^3 brick: 0 where a sample may be non-transparent; steps I and V cast LAO rays only there", true},
    {Resource::LabelVolume, "label volume", "R16UI 3D + RGBA32F 1D", "labels.glsl: label ids on the scan grid, a style per id", true},
    {Resource::DrilledRemoval, "drilled removal", "R8 3D + R8UI 3D", "drill_removal.glsl: drilled fraction per voxel; per 4^3 brick, within the dilation radius of a drilled voxel", true},
    {Resource::ClipMeshGeometry, "clip mesh geometry", "vertex + index buffers", "every clip mesh, scaled, in its local frame"},
    {Resource::ClipMaps, "clip maps (depth + dilated arrays)", "R32F 2D arrays", "steps II-III: Z and D maps of every mesh"},
    {Resource::ClippedOpacity, "V_o (clipped opacity)", "R16 3D", "step IV: opacity after anti-aliased clipping", true},
    {Resource::CategoryMask, "V_m (categories a/b/c)", "R8UI 3D", "step IV: clipped, affected, unaffected", true},
    {Resource::PrecomputedAo, "V_PAO (precomputed LAO)", "R16 3D", "step I: LAO without clipping", true},
    {Resource::Ambient, "V_AO (LAO under clipping)", "R16 3D", "step V: the ambient factor the integrators read", true},
    {Resource::RecomputeList, "recompute list", "uint32 buffer", "step V: the voxels to recompute of one chunk of at most 16384 visited bricks (compacted dispatch)", true},
    {Resource::VisitedBricks, "visited bricks", "uint32 buffer", "steps IV and V: the bricks they visit; step IV flags those whose V_o changed or whose LAO can", true},
    {Resource::LaoDirections, "LAO directions", "vec4 buffer", "the K rays of eq. 3 with their weights"},
    {Resource::TubeGeometry, "tube geometry", "vertex buffers", "tubes (triangles or impostor points) or illuminated lines"},
    {Resource::GBuffer, "G-buffer + partial occlusion", "RGBA16F/R32F/R32UI x2, D32F, bits", "tube colour, normal, depth; occlusion at the surface; impostors' nearest depth and segment, and candidates"},
    {Resource::OcclusionBuffers, "DOS occlusion buffers (2, ping-pong)", "RG32F 2D x2", "the slab pass's cone-blurred visibility"},
    {Resource::OutputImage, "output image", "RGBA32F 2D", "the frame"},
    {Resource::PreviewImage, "preview image", "RGBA32F 2D", "the viewer's preview frames"},
    {Resource::IsmosLayers, "ISMOS depth layers + opacities", "RGBA32F 2D x2", "seed 003 sec. 3.6: z = 1 - depth of 4 layer fronts, their opacity"},
    {Resource::IsmosLayerBacks, "ISMOS layer backs", "RGBA32F 2D", "exact partial occlusion: where each layer ends"},
    {Resource::IsmosFit, "ISMOS transmittance fit", "R32F 2D", "seed 003 eq. 10: beta of T(z) ~ exp(-beta z^2)"},
    {Resource::IsmosLightSamples, "ISMOS light samples", "vec4 buffer", "seed 003 sec. 3.2: N points per light disk"},
};
static_assert(rowsInEnumOrder(kResources, &ResourceInfo::id, Resource::Count), "kResources is indexed by Resource");
}  // namespace

const ResourceInfo& resourceInfo(Resource id) { return kResources[static_cast<std::size_t>(id)]; }

}  // namespace curette
