// walls hatched: every other diagonal band of 6 px is darker (as the software renderer)
in vec4 v_color;
out vec4 frag;

void main() {
  bool dark = (int(floor((gl_FragCoord.x + gl_FragCoord.y) / 6.0)) & 1) == 1;
  frag = vec4(v_color.rgb * (dark ? 0.8 : 1.0), v_color.a);
}
