#version 330 core
in vec3 v_normal;
in vec3 v_colour;
in float v_crack;

uniform vec3 u_light;        // unit, towards the light, world frame
uniform vec3 u_crack_colour;
uniform vec3 u_highlight;    // added to the colour of a selected body or fragment (zero otherwise)

out vec4 f_colour;

void main() {
  vec3 n = normalize(v_normal);
  // Two-sided Lambert with a hemisphere ambient: an open or inward face still reads.
  float diffuse = abs(dot(n, u_light));
  vec3 base = mix(v_colour, u_crack_colour, v_crack);
  vec3 lit = base * (0.28 + 0.72 * diffuse);
  // Scene colours are linear (glTF base colours); the framebuffer is shown as sRGB.
  f_colour = vec4(pow(lit + u_highlight, vec3(1.0 / 2.2)), 1.0);
}
