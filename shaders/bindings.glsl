// Texture and image units, one table for every shader (mirrored by render/bindings.h; a test checks they
// agree). Passes bind by these names so no two includes can collide on a unit.
#define BINDING_VOLUME 0            // sampler3D: the data volume V
#define BINDING_TRANSFER_FUNCTION 1 // sampler1D: rgb + opacity per unit length
#define BINDING_GRADIENT_OPACITY 2  // sampler1D: opacity factor over |gradient|
#define BINDING_OCCUPANCY 3         // sampler3D: per-brick "may be non-transparent" flags
#define BINDING_AMBIENT 4           // sampler3D: V_AO (cao/lao shading)
#define BINDING_OPACITY 5           // sampler3D: V_o, clipped opacity (LAO input)
#define BINDING_PRECOMPUTED_AO 6    // sampler3D: V_PAO
#define BINDING_MASK 7              // usampler3D: V_m
#define BINDING_CLIP_DEPTH 8        // sampler2DArray: per-mesh depth maps (Z_front, Z_back, peeled layers)
#define BINDING_CLIP_DILATED 9      // sampler2DArray: per-mesh dilated maps (D_front, D_back, ...)
#define BINDING_OCCLUSION_PREVIOUS 10  // sampler2D rg32f: the slab pass's previous occlusion buffer
#define BINDING_TUBE_DEPTH 11       // sampler2D r32f: G-buffer view depth of the nearest tube surface (0: none)
#define BINDING_TUBE_COLOR 12       // sampler2D rgba16f: G-buffer surface colour
#define BINDING_TUBE_NORMAL 13      // sampler2D rgba16f: G-buffer world normal (tubes) or tangent (lines), w: kind
#define BINDING_PARTIAL_OCCLUSION 14   // sampler2D r32f: volume occlusion at each tube surface
#define BINDING_LABEL_IDS 15        // usampler3D r16ui: label ids on the scan grid (labels.glsl)
#define BINDING_LABEL_STYLES 16     // sampler1D rgba32f: per label id rgb + opacity per unit length
#define BINDING_ISMOS_LAYER_FRONT 17   // sampler2D rgba32f: ISMOS z = 1 - depth of up to 4 layer fronts (-1: none)
#define BINDING_ISMOS_LAYER_ALPHA 18   // sampler2D rgba32f: ISMOS opacity of each layer
#define BINDING_ISMOS_LAYER_BACK 19    // sampler2D rgba32f: ISMOS z of each layer's last sample (exact opacity)
#define BINDING_ISMOS_FIT 20           // sampler2D r32f: ISMOS beta of the transmittance fit exp(-beta z^2)
#define BINDING_SEEN_BRICKS 21         // sampler3D r8: per seen brick 0 where a visible sample may read its LAO (steps I, V)
#define BINDING_CLIP_NORMALS 22        // sampler2DArray rg16_snorm: per depth-map pixel the mesh-local surface normal (octahedral)
#define BINDING_LABEL_FIELD 23         // sampler3D rgba8: the shown labels' smoothed (rgb * shown, shown) on the scan grid
#define BINDING_LABEL_OPACITY 24       // sampler3D r8: ... and their smoothed opacity * shown
#define BINDING_DRILLED_FRACTION 25    // sampler3D r8: per voxel the drilled fraction (plan/removal_volume.h)
#define BINDING_DRILL_NEAR_BRICKS 26   // usampler3D r8ui: per 4^3 brick 1 within the dilation radius of a drilled voxel
#define BINDING_TUBE_IMPOSTOR_POINTS 27  // usamplerBuffer rgba32ui: impostor tube points (xyz float bits, colour and flags)
#define BINDING_GRADIENT_VOLUME 28       // sampler3D rgba16_snorm: phong's central differences per voxel, padded (8-bit scans)

#define IMAGE_OUTPUT 0              // image2D: the rendered RGBA
#define IMAGE_OPACITY 1             // image3D r16: V_o written by step IV
#define IMAGE_MASK 2                // uimage3D r8ui: V_m written by step IV
#define IMAGE_AMBIENT 3             // image3D r16: V_AO (or V_PAO in step I) written by step V
#define IMAGE_DILATION 4            // image2DArray r32f: dilated map written by step III
#define IMAGE_OCCLUSION_NEXT 5      // image2D rg32f: the slab pass's next occlusion buffer
#define IMAGE_PARTIAL_OCCLUSION 6   // image2D r32f: written by the slab pass at each tube surface's depth
#define IMAGE_ISMOS_LAYER_FRONT 7   // image2D rgba32f: ISMOS pass 1 writes the layer fronts
#define IMAGE_ISMOS_LAYER_ALPHA 8   // image2D rgba32f: ... the layer opacities
#define IMAGE_ISMOS_LAYER_BACK 9    // image2D rgba32f: ... the layer backs (exact opacity only)
#define IMAGE_ISMOS_FIT 10          // image2D r32f: ... beta (transmittance fit only)
#define IMAGE_TUBE_NEAREST_DEPTH 11     // uimage2D r32ui: impostor tubes, per pixel the nearest view depth's float bits
#define IMAGE_TUBE_NEAREST_SEGMENT 12   // uimage2D r32ui: ... the first segment at that depth
#define IMAGE_TUBE_COLOR 13             // image2D rgba16f: the G-buffer colour written by the impostor tubes
#define IMAGE_TUBE_NORMAL 14            // image2D rgba16f: ... the normal + kind
#define IMAGE_TUBE_DEPTH 15             // image2D r32f: ... the view depth
#define IMAGE_GRADIENT_VOLUME 16        // image3D rgba16_snorm: the gradient volume (gradient_volume.comp)

#define SSBO_SAMPLE_COUNTER 0       // uint: samples taken (bench only)
#define SSBO_LAO_DIRECTIONS 1       // vec4[]: LAO step in texture space, weight / (K * M)
#define SSBO_VISIT_BRICKS 2         // uint[]: the bricks steps IV and V visit (visit_bricks.glsl)
#define SSBO_RECOMPUTE_LIST 3       // uint count, uint voxels[]: category-b voxels (step V, compacted)
#define SSBO_DISPATCH 4             // uvec3: indirect dispatch size of the compacted step V
#define SSBO_ANTI_ALIASING 5        // vec4[]: the N extra anti-aliasing offsets of step IV
#define SSBO_POISSON_DISK 8         // vec2[]: vicinity-occlusion samples in the unit disk
#define SSBO_PROBE_POINTS 6         // vec4[]: world points the clip probe tests (clip_probe.comp)
#define SSBO_PROBE_RESULTS 7        // uint[]: per point bit 0 inside, bit 1 dilated, bit 2 near
#define SSBO_ISMOS_LIGHT_SAMPLES 10  // vec4[]: ISMOS light samples in texture space, N per light
#define SSBO_REMOVAL_COUNTS 9       // uint[]: per voxel of a box, clip samples inside a mesh (removal_count.comp)
#define SSBO_TUBE_RINGS 11          // TubeRing[]: one batch of swept rings (tube_build.comp)
#define SSBO_TUBE_STREAMLINES 12    // TubeStreamline[]: first ring, vertex and index, radius, sides, caps
#define SSBO_TUBE_CIRCLE 13         // vec2[]: cos, sin of 2 pi k / sides, sides * (sides - 1) / 2 + k
#define SSBO_TUBE_POSITIONS 14      // float[]: the batch's range of the tube position stream (x y z)
#define SSBO_TUBE_DIRECTIONS 15     // float[]: ... of the normal stream (x y z)
#define SSBO_TUBE_COLORS 16         // vec4[]: ... of the colour stream
#define SSBO_TUBE_INDICES 17        // uint[]: ... of the triangle index stream
#define SSBO_TILE_SPANS 18          // uvec2[]: per row of tiles, the columns a dispatch covers (tile_order.glsl)
#define SSBO_TUBE_CANDIDATES 19     // uint[]: impostor tubes, a bit per point: its segment was the nearest at a pixel when phase 0 tested it

#define UBO_CLIP_MESHES 0           // ClipMeshGpu[MAX_CLIP_MESHES]: per-mesh clipping camera

// G-buffer kinds (normal.w).
#define SURFACE_NONE 0.0
#define SURFACE_TUBE 1.0
#define SURFACE_LINE 2.0

// Categories of V_m (CAO Fig. 5): a clipped, b affected by clipping, c unaffected.
#define CATEGORY_CLIPPED 0u
#define CATEGORY_AFFECTED 1u
#define CATEGORY_UNAFFECTED 2u
