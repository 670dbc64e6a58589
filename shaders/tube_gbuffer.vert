#version 450
// Tubes (and illuminated lines) into the G-buffer (seed 000 section 3.1.1): colour, world normal or tangent,
// view depth. World-space geometry: tracts and volume share world millimetres.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normalOrTangent;
layout(location = 2) in vec4 color;
uniform mat4 viewProjection;
out vec3 worldPosition;
out vec3 worldDirection;
out vec4 surfaceColor;
void main() {
    worldPosition = position;
    worldDirection = normalOrTangent;
    surfaceColor = color;
    gl_Position = viewProjection * vec4(position, 1.0);
    // The passes that read the G-buffer index it by the ray caster's pixels, whose row 0 is the top of the
    // picture (pixel_ray.glsl); GL rasterises row 0 at the bottom, so mirror y to share one pixel grid.
    gl_Position.y = -gl_Position.y;
}
