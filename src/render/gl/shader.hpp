// shader programs from shaders/<name>.vert and .frag, with shaders/common.glsl prepended
#pragma once
#include <string>

#include "render/gl/gl_api.hpp"

namespace gs::gl {

/// vertex attribute locations: declared here once, bound by name before every link
enum Loc : GLuint { kPos = 0, kColor = 1, kUv = 2, kCenter = 3, kShape = 4, kFill = 5, kSides = 6 };
struct AttribBinding {
  const char* name;
  GLuint location;
};
inline constexpr AttribBinding kAttribs[] = {
    {"a_pos", kPos},     {"a_color", kColor}, {"a_uv", kUv},      {"a_center", kCenter},
    {"a_shape", kShape}, {"a_fill", kFill},   {"a_sides", kSides}};

/// the shader folder: $GS_SHADER_DIR if set, else shaders/ beside the executable (build tree,
/// or share/gransim/shaders of an install), else the GS_SHADER_DIR the build was given
std::string shader_dir();

/// compile and link <dir>/<name>.vert + <dir>/<name>.frag (GLSL 3.30 core); throws RenderError
/// with the file name and the compiler log
GLuint build_program(const Api& gl, const std::string& name);

}  // namespace gs::gl
