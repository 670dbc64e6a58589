// Shading modes, mirrored by curette::ShadingMode (render/model/shading_mode.h). The ray caster is compiled once
// per mode with SHADING set to one of these.
#define SHADING_SOLID 0   // emission-absorption with the TF colour
#define SHADING_PHONG 1   // Blinn-Phong with gradient normals
#define SHADING_LAO 2     // ambient from V_AO, LAO recomputed for every voxel every frame
#define SHADING_CAO 3     // ambient from V_AO, Contextual Ambient Occlusion
#define SHADING_DOS 4     // directional occlusion shading (slab pass)
#define SHADING_ISMOS 5   // image-space multidirectional occlusion (seed 003): pass 1 is compiled with its
                          // base's value (phong or solid) and ISMOS_LAYERS; pass 2 is ismos_occlusion.comp
