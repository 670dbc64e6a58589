// Where a voxel, or a texture coordinate of the volume, lies in a volume-sized texture: the one mapping every
// access to V, V_o, V_m, V_PAO, V_AO, the label textures and the drilled fraction goes through
// (render/model/volume_layout.h; binder VolumeLayoutPiece, render/shader_pieces.h). Bricks keep the unfolded
// lattice and are indexed as before.
//   VOLUME_SAMPLE(s, tex)             trilinear, CLAMP_TO_EDGE at the volume's faces
//   VOLUME_SAMPLE_ZERO_BORDER(s, tex) trilinear, zero beyond the volume's faces (V_o: CLAMP_TO_BORDER)
//   VOLUME_FETCH(s, v)                voxel v's texel
//   VOLUME_STORE(image, v, value)     write voxel v (both its texels when it lies on a cut)
// Without VOLUME_FOLD (the volume fits one texture) these are the plain GL calls: the code, and so every image,
// of an unfolded volume is what it was. With it, VOLUME_FOLD_AXIS (cut into pieces of volumeFold.x + 1 voxels,
// one of overlap) and VOLUME_ACROSS_AXIS (the pieces side by side, volumeFold.z texels apart, a zero texel
// between) are compiled in; tex stays the unfolded coordinate ((index + 0.5) / dims) everywhere else.
#ifdef VOLUME_FOLD
uniform ivec3 volumeFold;        // stride, pieces, across pitch (render/model/volume_layout.h)
uniform vec3 volumeFoldDims;     // the volume's voxels
uniform vec3 volumeFoldTexels;   // the texture's texels

ivec3 volumeTexelIn(ivec3 v, int piece) {
    v[VOLUME_FOLD_AXIS] -= piece * volumeFold.x;
    v[VOLUME_ACROSS_AXIS] += piece * volumeFold.z;
    return v;
}
ivec3 volumeTexel(ivec3 v) { return volumeTexelIn(v, min(v[VOLUME_FOLD_AXIS] / volumeFold.x, volumeFold.y - 1)); }
// The first voxel of every piece but the first is also the previous piece's last.
bool volumeHasTwin(ivec3 v) {
    int i = v[VOLUME_FOLD_AXIS];
    return i > 0 && i % volumeFold.x == 0 && i / volumeFold.x < volumeFold.y;
}
ivec3 volumeTwinTexel(ivec3 v) { return volumeTexelIn(v, v[VOLUME_FOLD_AXIS] / volumeFold.x - 1); }

// The piece holds both trilinear neighbours along the fold axis (floor(t - 0.5) and the next), so a sample never
// blends two pieces; across, a CLAMP_TO_EDGE texture clamps within its piece (the hardware clamps at the
// texture's faces only) and a zero-border one reads the zero texel between pieces as the border.
vec3 volumeTextureCoord(vec3 tex, bool clampToEdge) {
    float a = tex[VOLUME_FOLD_AXIS] * volumeFoldDims[VOLUME_FOLD_AXIS];
    float b = tex[VOLUME_ACROSS_AXIS] * volumeFoldDims[VOLUME_ACROSS_AXIS];
    if (clampToEdge) {
        a = min(a, volumeFoldDims[VOLUME_FOLD_AXIS] - 0.5);   // the last piece's tail holds no voxel
        b = clamp(b, 0.5, volumeFoldDims[VOLUME_ACROSS_AXIS] - 0.5);
    }
    int piece = clamp(int(floor(a - 0.5)) / volumeFold.x, 0, volumeFold.y - 1);
    tex[VOLUME_FOLD_AXIS] = (a - float(piece * volumeFold.x)) / volumeFoldTexels[VOLUME_FOLD_AXIS];
    tex[VOLUME_ACROSS_AXIS] = (b + float(piece * volumeFold.z)) / volumeFoldTexels[VOLUME_ACROSS_AXIS];
    return tex;
}
#define VOLUME_SAMPLE(s, tex) texture(s, volumeTextureCoord(tex, true))
#define VOLUME_SAMPLE_ZERO_BORDER(s, tex) texture(s, volumeTextureCoord(tex, false))
#define VOLUME_FETCH(s, v) texelFetch(s, volumeTexel(v), 0)
#define VOLUME_STORE(image, v, value)                                                  \
    do {                                                                               \
        imageStore(image, volumeTexel(v), value);                                      \
        if (volumeHasTwin(v)) imageStore(image, volumeTwinTexel(v), value);            \
    } while (false)
#else
#define VOLUME_SAMPLE(s, tex) texture(s, tex)
#define VOLUME_SAMPLE_ZERO_BORDER(s, tex) texture(s, tex)
#define VOLUME_FETCH(s, v) texelFetch(s, v, 0)
#define VOLUME_STORE(image, v, value) imageStore(image, v, value)
#endif
