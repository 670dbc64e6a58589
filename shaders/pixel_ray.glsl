// The camera ray through a pixel centre: one definition for every pass that works per pixel (the ray caster,
// the slab pass, the tube compositor). Image row 0 is the top of the picture.
// Binder: CameraRayPiece (render/shader_pieces.h).

uniform mat4 inverseViewProjection;  // clip space -> world
uniform vec3 eyeWorld;
uniform ivec2 outputSize;

bool outsideImage(ivec2 pixel) { return any(greaterThanEqual(pixel, outputSize)); }

// Unit direction, world, from the eye through the centre of `pixel`.
vec3 pixelRayDirection(ivec2 pixel) {
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(outputSize) * 2.0 - 1.0;
    ndc.y = -ndc.y;
    vec4 farPoint = inverseViewProjection * vec4(ndc, 1.0, 1.0);
    return normalize(farPoint.xyz / farPoint.w - eyeWorld);
}
