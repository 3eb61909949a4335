// disk by signed distance d (px, > 0 outside): coverage clamp(0.5 - d, 0, 1), outline band inside
in vec2 v_local;
flat in float v_radius;
flat in vec4 v_fill;
uniform float u_outline_width;  // px, 0 = no outline
uniform vec4 u_outline;         // outline colour
out vec4 frag;

void main() {
  float d = length(v_local) - v_radius;
  float coverage = clamp(0.5 - d, 0.0, 1.0);
  if (coverage <= 0.0) discard;
  float t = u_outline_width > 0.0 ? clamp(-d - u_outline_width + 0.5, 0.0, 1.0) : 1.0;
  frag = vec4(mix(u_outline.rgb, v_fill.rgb, t), v_fill.a * coverage);
}
