// "No data" (NaN/Inf voxels) in gradients. Such voxels store a value far below the data (base/volume.h
// noDataTexelBelow), which the TF table makes transparent; a central difference across one would see a
// gradient as large as that drop, and gradient opacity would turn the border of every no-data region into an
// opaque shell. So where a neighbour is no data the difference is one-sided (the sample and the neighbour on
// the other side), and an axis with no data on both sides has no gradient. Compiled in only for a volume
// with no-data voxels (NoDataPiece, render/shader_pieces.h): every other volume keeps its gradients bit for bit.
// The CPU twin is render/reference/volume_sampler.h (VolumeSampler).

#ifdef NO_DATA
uniform float noDataSide;    // the sign of the texel -> value map
uniform float noDataBound;   // a stored value t is no data when t * noDataSide < noDataBound (NoDataSamples)
bvec3 noDataSamples(vec3 texels) { return lessThan(texels * noDataSide, vec3(noDataBound)); }
#endif

// Twice the index gradient along each axis from the stored values one voxel below and above and at the
// sample itself (the central difference plus - minus where both are data).
vec3 differencesAcross(vec3 minus, vec3 centre, vec3 plus) {
#ifdef NO_DATA
    bvec3 below = noDataSamples(minus), above = noDataSamples(plus);
    vec3 belowIsData = mix(plus - minus, 2.0 * (centre - minus), above);
    vec3 belowIsNoData = mix(2.0 * (plus - centre), vec3(0.0), above);
    return mix(belowIsData, belowIsNoData, below);   // selections (bvec), so the no-data values never mix in
#else
    return plus - minus;
#endif
}
