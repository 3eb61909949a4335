// instanced regular n-gons with their true shape and orientation: instance i is a fan of
// a_sides triangles made from gl_VertexID (triangle k = centre, vertex k, vertex k+1);
// triangles beyond a_sides are sent outside the clip volume and vanish
in vec2 a_center;  // centre, px
in vec2 a_shape;   // circumradius, px; orientation, rad
in vec4 a_fill;    // fill colour
in int a_sides;    // number of sides

out float v_edge;     // distance to this fan triangle's outer edge, px (affine, so exact)
flat out vec4 v_fill;

void main() {
  int tri = gl_VertexID / 3;
  int corner = gl_VertexID - 3 * tri;
  v_fill = a_fill;
  v_edge = 0.0;
  if (tri >= a_sides) {
    gl_Position = vec4(0.0, 0.0, -2.0, 1.0);
    return;
  }
  float step = 6.283185307179586 / float(a_sides);
  vec2 p = vec2(0.0);
  if (corner == 0) {
    // the centre lies one apothem from every edge
    v_edge = a_shape.x * cos(0.5 * step);
  } else {
    // vertex k at angle θ + 2πk/n
    float a = a_shape.y + step * float(tri + corner - 1);
    p = a_shape.x * vec2(cos(a), sin(a));
  }
  gl_Position = canvas_to_clip(a_center + p);
}
