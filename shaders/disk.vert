// instanced disks: a quad one pixel larger than the disk, corners from gl_VertexID
// (triangle strip (-1,-1), (1,-1), (-1,1), (1,1))
in vec2 a_center;  // centre, px
in vec2 a_shape;   // radius, px; orientation, rad (unused)
in vec4 a_fill;    // fill colour

out vec2 v_local;  // offset from the centre, px
flat out float v_radius;
flat out vec4 v_fill;

void main() {
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
  v_radius = a_shape.x;
  v_fill = a_fill;
  v_local = corner * (a_shape.x + 1.0);
  gl_Position = canvas_to_clip(a_center + v_local);
}
