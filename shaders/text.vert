// text: one quad per glyph, texture coordinates into the glyph atlas
in vec2 a_pos;    // px
in vec2 a_uv;     // atlas coordinates, 0..1
in vec4 a_color;  // text colour
out vec2 v_uv;
out vec4 v_color;

void main() {
  v_uv = a_uv;
  v_color = a_color;
  gl_Position = canvas_to_clip(a_pos);
}
