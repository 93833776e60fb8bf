#version 330 core
// Grid, axes and the crack-line overlay: coloured line segments.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_colour;

uniform mat4 u_view_projection;
uniform vec3 u_offset;

out vec3 v_colour;

void main() {
  v_colour = a_colour;
  gl_Position = u_view_projection * vec4(a_position + u_offset, 1.0);
}
