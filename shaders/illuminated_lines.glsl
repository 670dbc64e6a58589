// Phong lighting of lines (codimension 2), seed 004 eq. 3.12-3.15: the normal is the one coplanar with the
// light and the tangent, so everything is expressed with L.T and V.T. Mirrors
// curette::illuminatedLineColor (render/tube_geometry.cpp), its CPU oracle.
//   L.N = sqrt(1 - (L.T)^2)                                          (3.12)
//   V.R = (L.T)(V.T) - sqrt(1 - (L.T)^2) sqrt(1 - (V.T)^2)           (3.13)
//   I_diffuse = kd (L.N)^p, excess-brightness exponent p (Banks: 4.8; the chapter uses 2)   (3.14, 3.15)
vec2 illuminatedLineTerms(vec3 tangent, vec3 toLight, vec3 toViewer, float diffuseExponent, float shininess) {
    float lt = dot(toLight, tangent), vt = dot(toViewer, tangent);
    float ln = sqrt(max(1.0 - lt * lt, 0.0));
    float vr = lt * vt - ln * sqrt(max(1.0 - vt * vt, 0.0));
    return vec2(pow(ln, diffuseExponent), pow(max(vr, 0.0), shininess));
}
