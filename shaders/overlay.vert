// overlays (colour bar, arrows, frames, force chains, panels): coloured triangles, px
in vec2 a_pos;    // px
in vec4 a_color;  // colour
out vec4 v_color;

void main() {
  v_color = a_color;
  gl_Position = canvas_to_clip(a_pos);
}
