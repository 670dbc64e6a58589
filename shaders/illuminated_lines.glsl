// Phong lighting of lines (codimension 2), seed 004 eq. 3.12-3.15: the normal is the one coplanar with the
// light and the tangent, so everything is expressed with L.T and V.T. Mirrors
// curette::illuminatedLineColor (render/model/tube_geometry.cpp), its CPU oracle.
// Sign conventions: here L (toLight) and V (toViewer) both point away from the line. Eq. 3.13 is written with
// L the incident direction (towards the line) and V towards the viewer; with L flipped, R = 2 (L.N) N - L
// and the highlight term becomes
//   L.N = sqrt(1 - (L.T)^2)                                          (3.12)
//   V.R = sqrt(1 - (L.T)^2) sqrt(1 - (V.T)^2) - (L.T)(V.T)           (3.13, L and V pointing away)
//   I_diffuse = kd (L.N)^p, excess-brightness exponent p (Banks: 4.8; the chapter uses 2)   (3.14, 3.15)
// so a headlit line across the view (L = V perpendicular to T) gets the full highlight and a line pointing at
// the eye (L = V parallel to T) none.
vec2 illuminatedLineTerms(vec3 tangent, vec3 toLight, vec3 toViewer, float diffuseExponent, float shininess) {
    float lt = dot(toLight, tangent), vt = dot(toViewer, tangent);
    float ln = sqrt(max(1.0 - lt * lt, 0.0));
    float vr = ln * sqrt(max(1.0 - vt * vt, 0.0)) - lt * vt;
    return vec2(pow(ln, diffuseExponent), pow(max(vr, 0.0), shininess));
}
