// loading the GL entry points by name
#include "render/gl/gl_api.hpp"

#include "render/renderer.hpp"

namespace gs::gl {

void Api::load(void (*(*get)(const char*))()) {
  // each pointer from its "gl"-prefixed name; a missing one means the context is unusable
#define GS_GL_LOAD(type, name)                    \
  name = reinterpret_cast<type>(get("gl" #name)); \
  if (!name) throw RenderError("OpenGL entry point gl" #name " is not available");
  GS_GL_FUNCTIONS(GS_GL_LOAD)
#undef GS_GL_LOAD
}

std::string error_name(GLenum e) {
  switch (e) {
    case GL_NO_ERROR:
      return "";
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    default:
      return "GL error " + std::to_string(e);
  }
}

}  // namespace gs::gl
