// polygon fill with an anti-aliased outline band of u_outline_width px inside the edge
// (the outer edge itself is anti-aliased by MSAA coverage)
in float v_edge;
flat in vec4 v_fill;
uniform float u_outline_width;  // px, 0 = no outline
uniform vec4 u_outline;         // outline colour
out vec4 frag;

void main() {
  float t = u_outline_width > 0.0 ? clamp(v_edge - u_outline_width + 0.5, 0.0, 1.0) : 1.0;
  frag = vec4(mix(u_outline.rgb, v_fill.rgb, t), v_fill.a);
}
