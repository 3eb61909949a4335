// shared by every shader (prepended after the #version line by the loader):
// the canvas is in pixels with the origin at the bottom-left corner and y up.
// Attribute locations are bound once, by name, from src/render/gl/shader.hpp.
uniform vec2 u_canvas;  // canvas size, px

// canvas pixels to clip space
vec4 canvas_to_clip(vec2 p) { return vec4(2.0 * p / u_canvas - 1.0, 0.0, 1.0); }
