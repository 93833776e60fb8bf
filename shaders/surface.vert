#version 330 core
// Bodies and fragments, flat-shaded: every triangle carries its own normal (a fracture surface is
// faceted, and a crack face must not blend into the outer face beside it).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_colour;
layout(location = 3) in float a_crack;  // 1 on a crack face, 0 on the body's own surface

uniform mat4 u_view_projection;
uniform vec3 u_offset;  // the fragment's move plus its exploded-view push, world units

out vec3 v_normal;
out vec3 v_colour;
out float v_crack;

void main() {
  v_normal = a_normal;
  v_colour = a_colour;
  v_crack = a_crack;
  gl_Position = u_view_projection * vec4(a_position + u_offset, 1.0);
}
