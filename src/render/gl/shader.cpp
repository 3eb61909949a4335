// loading, compiling and linking the shaders
#include "render/gl/shader.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "render/renderer.hpp"

namespace gs::gl {

namespace {

// a whole text file, or RenderError naming it
std::string read_text(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw RenderError("cannot read shader file " + path + " (set GS_SHADER_DIR?)");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// one stage: #version, common.glsl, the file; the log in the error names the file
GLuint compile(const Api& gl, GLenum stage, const std::string& path, const std::string& common) {
  const std::string src = "#version 330 core\n" + common + "\n#line 1\n" + read_text(path);
  const GLuint sh = gl.CreateShader(stage);
  const char* text = src.c_str();
  gl.ShaderSource(sh, 1, &text, nullptr);
  gl.CompileShader(sh);
  GLint ok = 0;
  gl.GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    gl.GetShaderInfoLog(sh, sizeof log, nullptr, log);
    gl.DeleteShader(sh);
    throw RenderError("shader " + path + " does not compile: " + log);
  }
  return sh;
}

}  // namespace

std::string shader_dir() {
  if (const char* env = std::getenv("GS_SHADER_DIR"); env && *env) return env;
  // beside the executable: the build tree (build/../shaders) or an install
  // (bin/../share/gransim/shaders), so a moved or installed binary finds its own
  std::error_code ec;
  const std::filesystem::path exe =
      std::filesystem::read_symlink("/proc/self/exe", ec).parent_path();
  if (!ec)
    for (const auto& d : {exe / ".." / "shaders", exe / ".." / "share" / "gransim" / "shaders"})
      if (std::filesystem::exists(d / "common.glsl", ec)) return d.lexically_normal().string();
#ifdef GS_SHADER_DIR
  return GS_SHADER_DIR;
#else
  return "shaders";
#endif
}

GLuint build_program(const Api& gl, const std::string& name) {
  const std::string dir = shader_dir();
  const std::string common = read_text(dir + "/common.glsl");
  const GLuint vs = compile(gl, GL_VERTEX_SHADER, dir + "/" + name + ".vert", common);
  const GLuint fs = compile(gl, GL_FRAGMENT_SHADER, dir + "/" + name + ".frag", common);
  // attribute locations by name, then link
  const GLuint prog = gl.CreateProgram();
  gl.AttachShader(prog, vs);
  gl.AttachShader(prog, fs);
  for (const auto& a : kAttribs) gl.BindAttribLocation(prog, a.location, a.name);
  gl.LinkProgram(prog);
  gl.DeleteShader(vs);
  gl.DeleteShader(fs);
  GLint ok = 0;
  gl.GetProgramiv(prog, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    gl.GetProgramInfoLog(prog, sizeof log, nullptr, log);
    gl.DeleteProgram(prog);
    throw RenderError("shader program " + dir + "/" + name + " does not link: " + log);
  }
  return prog;
}

}  // namespace gs::gl
