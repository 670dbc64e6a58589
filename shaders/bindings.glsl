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

#define IMAGE_OUTPUT 0              // image2D: the rendered RGBA
