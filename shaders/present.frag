#version 450
// Shows the rendered image (premultiplied RGBA, row 0 at the top) over the background colour.
in vec2 uv;
out vec4 color;
layout(binding = 0) uniform sampler2D image;
uniform vec4 background;
void main() {
    vec4 p = texture(image, vec2(uv.x, 1.0 - uv.y));
    color = vec4(p.rgb + (1.0 - p.a) * background.a * background.rgb, 1.0);
}
