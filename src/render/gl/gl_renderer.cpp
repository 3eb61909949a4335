// the OSMesa backend: draw FrameData with GL 3.3 core into a 4× multisampled framebuffer and
// resolve it into OSMesa's own (top-row-first) buffer, which becomes the Image
#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <map>

#include "render/gl/context.hpp"
#include "render/gl/gl_api.hpp"
#include "render/gl/shader.hpp"
#include "render/renderer.hpp"

namespace gs {

namespace {

using gl::Api;

/// one vertex of a glyph quad, px and atlas coordinates
struct GlyphVertex {
  float x, y, u, v;
  Rgba8 color;
};

/// most polygon sides drawn (the frame builder turns finer n-gons into disks)
constexpr int kMaxSides = 64;

/// a program and the uniforms it may use (-1 when it has none of that name)
struct Program {
  GLuint id = 0;
  GLint canvas = -1, outline_width = -1, outline = -1, atlas = -1;
};

class GlRenderer final : public Renderer {
 public:
  GlRenderer() : fonts_(default_fonts()) {
    // a current context first, then the entry points, the version check and the shaders
    ctx_.make_current(16, 16);
    gl_.load(&gl::OsMesaContext::proc);
    GLint major = 0, minor = 0;
    gl_.GetIntegerv(GL_MAJOR_VERSION, &major);
    gl_.GetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 33)
      throw RenderError("OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
                        " found, 3.3 needed");
    gl_.GetIntegerv(GL_MAX_SAMPLES, &max_samples_);
    gl_.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size_);
    polygon_ = program("polygon");
    disk_ = program("disk");
    wall_ = program("wall");
    overlay_ = program("overlay");
    text_ = program("text");
    make_arrays();
    version_ = reinterpret_cast<const char*>(gl_.GetString(GL_VERSION));
    device_ = reinterpret_cast<const char*>(gl_.GetString(GL_RENDERER));
    check("initialisation");
  }

  ~GlRenderer() override {
    // the context must be current to delete its objects
    try {
      ctx_.make_current(16, 16);
    } catch (...) {
      return;
    }
    free_targets();
    for (auto& [atlas, tex] : textures_) gl_.DeleteTextures(1, &tex.second);
    for (Program* p : {&polygon_, &disk_, &wall_, &overlay_, &text_}) gl_.DeleteProgram(p->id);
    gl_.DeleteVertexArrays(3, vao_);
    gl_.DeleteBuffers(3, vbo_);
  }

  std::string describe() const override {
    const std::string msaa = wanted_ == 0 ? "MSAA up to " + std::to_string(max_samples_) + "x"
                                          : std::to_string(samples_) + "x MSAA";
    return "OSMesa OpenGL " + version_ + " (" + ctx_.profile() + " profile), " + device_ + ", " +
           msaa;
  }

  Image render(const FrameData& f) override {
    if (f.width < 1 || f.height < 1 || f.width > max_size_ || f.height > max_size_)
      throw RenderError("frame size " + std::to_string(f.width) + "x" + std::to_string(f.height) +
                        " exceeds the GL limit of " + std::to_string(max_size_));
    ctx_.make_current(f.width, f.height);
    target(f.width, f.height, std::clamp(f.msaa, 1, std::max(1, max_samples_)));

    // clear to the background, blend straight alpha (the destination stays opaque)
    gl_.BindFramebuffer(GL_FRAMEBUFFER, ms_fbo_);
    gl_.Viewport(0, 0, f.width, f.height);
    gl_.Disable(GL_DEPTH_TEST);
    gl_.Disable(GL_CULL_FACE);
    gl_.ClearColor(f.background.r / 255.0f, f.background.g / 255.0f, f.background.b / 255.0f, 1.0f);
    gl_.Clear(GL_COLOR_BUFFER_BIT);
    gl_.Enable(GL_BLEND);
    gl_.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    if (samples_ > 1) gl_.Enable(GL_MULTISAMPLE);

    // walls in the view, particles in their clip box, world overlays in the view, the rest
    gl_.Enable(GL_SCISSOR_TEST);
    scissor(f.view_clip, f);
    triangles(wall_, f.walls, f);
    scissor(f.particle_clip, f);
    shapes(polygon_, f.polygons, f, true);
    shapes(disk_, f.disks, f, false);
    scissor(f.view_clip, f);
    triangles(overlay_, f.world_overlay, f);
    gl_.Disable(GL_SCISSOR_TEST);
    triangles(overlay_, f.overlay, f);
    text(f);

    // resolve the samples straight into OSMesa's buffer (framebuffer 0) and wait for it:
    // the buffer then holds the picture top row first (OSMESA_Y_UP = 0), so no glReadPixels
    // and no flip are needed (faster than a resolve FBO + glReadPixels + flip; byte-identical
    // with MSAA, a handful of edge pixels differ without it)
    if (ms_fbo_) {
      gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, ms_fbo_);
      gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
      gl_.BlitFramebuffer(0, 0, f.width, f.height, 0, 0, f.width, f.height, GL_COLOR_BUFFER_BIT,
                          GL_NEAREST);
    }
    gl_.Finish();
    check("drawing");
    Image img(f.width, f.height);
    std::memcpy(img.rgba.data(), ctx_.pixels(), img.rgba.size());
    for (std::size_t k = 3; k < img.rgba.size(); k += 4) img.rgba[k] = 255;
    return img;
  }

 private:
  // a program and its uniform locations
  Program program(const std::string& name) {
    Program p;
    p.id = gl::build_program(gl_, name);
    p.canvas = gl_.GetUniformLocation(p.id, "u_canvas");
    p.outline_width = gl_.GetUniformLocation(p.id, "u_outline_width");
    p.outline = gl_.GetUniformLocation(p.id, "u_outline");
    p.atlas = gl_.GetUniformLocation(p.id, "u_atlas");
    return p;
  }

  // three vertex layouts: shape instances, coloured vertices, glyph vertices
  void make_arrays() {
    gl_.GenVertexArrays(3, vao_);
    gl_.GenBuffers(3, vbo_);
    auto attrib = [&](GLuint loc, int n, GLenum type, bool norm, std::size_t stride,
                      std::size_t offset, bool per_instance) {
      gl_.EnableVertexAttribArray(loc);
      const void* off = reinterpret_cast<const void*>(offset);
      if (type == GL_INT)
        gl_.VertexAttribIPointer(loc, n, type, static_cast<GLsizei>(stride), off);
      else
        gl_.VertexAttribPointer(loc, n, type, norm, static_cast<GLsizei>(stride), off);
      if (per_instance) gl_.VertexAttribDivisor(loc, 1);
    };
    // instances: centre, (radius, angle), fill, sides; one per instance
    gl_.BindVertexArray(vao_[0]);
    gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_[0]);
    const std::size_t si = sizeof(ShapeInstance);
    attrib(gl::kCenter, 2, GL_FLOAT, false, si, offsetof(ShapeInstance, cx), true);
    attrib(gl::kShape, 2, GL_FLOAT, false, si, offsetof(ShapeInstance, radius), true);
    attrib(gl::kFill, 4, GL_UNSIGNED_BYTE, true, si, offsetof(ShapeInstance, fill), true);
    attrib(gl::kSides, 1, GL_INT, false, si, offsetof(ShapeInstance, sides), true);
    // coloured triangles
    gl_.BindVertexArray(vao_[1]);
    gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_[1]);
    const std::size_t cv = sizeof(ColorVertex);
    attrib(gl::kPos, 2, GL_FLOAT, false, cv, offsetof(ColorVertex, x), false);
    attrib(gl::kColor, 4, GL_UNSIGNED_BYTE, true, cv, offsetof(ColorVertex, color), false);
    // glyph quads
    gl_.BindVertexArray(vao_[2]);
    gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_[2]);
    const std::size_t gv = sizeof(GlyphVertex);
    attrib(gl::kPos, 2, GL_FLOAT, false, gv, offsetof(GlyphVertex, x), false);
    attrib(gl::kUv, 2, GL_FLOAT, false, gv, offsetof(GlyphVertex, u), false);
    attrib(gl::kColor, 4, GL_UNSIGNED_BYTE, true, gv, offsetof(GlyphVertex, color), false);
    gl_.BindVertexArray(0);
  }

  // the multisampled framebuffer, remade when the size or the samples change; with one
  // sample (or when multisampling fails) everything is drawn straight into framebuffer 0
  void target(int w, int h, int samples) {
    if (w == tw_ && h == th_ && samples == wanted_) return;
    free_targets();
    tw_ = w, th_ = h, wanted_ = samples, samples_ = 1;
    if (samples <= 1) return;
    gl_.GenFramebuffers(1, &ms_fbo_);
    gl_.GenRenderbuffers(1, &ms_rb_);
    gl_.BindRenderbuffer(GL_RENDERBUFFER, ms_rb_);
    gl_.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, w, h);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, ms_fbo_);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, ms_rb_);
    if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE) {
      samples_ = samples;
    } else {
      std::fprintf(stderr, "gransim: no %dx multisampled framebuffer; drawing without MSAA\n",
                   samples);
      free_targets();
    }
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  }

  void free_targets() {
    if (ms_fbo_) gl_.DeleteFramebuffers(1, &ms_fbo_);
    if (ms_rb_) gl_.DeleteRenderbuffers(1, &ms_rb_);
    ms_fbo_ = ms_rb_ = 0;
  }

  // the scissor box of the pixels whose centres lie in a canvas rectangle
  void scissor(const std::array<float, 4>& rect, const FrameData& f) {
    const auto c = clip_pixels(rect, f.width, f.height);
    gl_.Scissor(c[0], c[1], std::max(0, c[2] - c[0]), std::max(0, c[3] - c[1]));
  }

  // the uniforms every program shares
  void use(const Program& p, const FrameData& f) {
    gl_.UseProgram(p.id);
    if (p.canvas >= 0)
      gl_.Uniform2f(p.canvas, static_cast<float>(f.width), static_cast<float>(f.height));
    if (p.outline_width >= 0) gl_.Uniform1f(p.outline_width, f.outline_px);
    const Rgba8& o = f.outline_color;
    if (p.outline >= 0)
      gl_.Uniform4f(p.outline, o.r / 255.0f, o.g / 255.0f, o.b / 255.0f, o.a / 255.0f);
    if (p.atlas >= 0) gl_.Uniform1i(p.atlas, 0);
  }

  // a triangle list of coloured vertices
  void triangles(const Program& p, const std::vector<ColorVertex>& v, const FrameData& f) {
    if (v.empty()) return;
    use(p, f);
    gl_.BindVertexArray(vao_[1]);
    gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_[1]);
    gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(ColorVertex)),
                   v.data(), GL_STREAM_DRAW);
    gl_.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(v.size()));
  }

  // instanced shapes: polygon fans of 3 × (most sides) vertices, or disk quads of 4
  void shapes(const Program& p, const std::vector<ShapeInstance>& s, const FrameData& f,
              bool polygons) {
    if (s.empty()) return;
    use(p, f);
    gl_.BindVertexArray(vao_[0]);
    gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_[0]);
    gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(s.size() * sizeof(ShapeInstance)),
                   s.data(), GL_STREAM_DRAW);
    const auto count = static_cast<GLsizei>(s.size());
    if (polygons) {
      int most = 3;
      for (const auto& i : s) most = std::max(most, std::min(i.sides, kMaxSides));
      gl_.DrawArraysInstanced(GL_TRIANGLES, 0, 3 * most, count);
    } else {
      gl_.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, count);
    }
  }

  // the texture of an atlas, uploaded on first use (R8 coverage)
  GLuint texture(const std::shared_ptr<const GlyphAtlas>& a) {
    auto& slot = textures_[a.get()];
    if (slot.second) return slot.second;
    slot.first = a;  // keep the atlas alive while its texture exists
    gl_.GenTextures(1, &slot.second);
    gl_.BindTexture(GL_TEXTURE_2D, slot.second);
    gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_R8, a->width, a->height, 0, GL_RED, GL_UNSIGNED_BYTE,
                   a->alpha.data());
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return slot.second;
  }

  // text: glyph quads grouped by atlas (one per font size), one draw each
  void text(const FrameData& f) {
    if (!fonts_ || f.text.empty()) return;
    std::map<std::shared_ptr<const GlyphAtlas>, std::vector<GlyphVertex>> batches;
    for (const TextItem& t : f.text) {
      auto atlas = fonts_(static_cast<int>(std::lround(t.size)));
      if (!atlas) continue;
      auto& v = batches[atlas];
      const float iw = 1.0f / atlas->width, ih = 1.0f / atlas->height;
      for (const GlyphQuad& q : layout_text(t, *atlas)) {
        const float u0 = q.ax * iw, u1 = (q.ax + q.aw) * iw;
        const float v0 = q.ay * ih, v1 = (q.ay + q.ah) * ih;  // atlas row 0 is the glyph top
        const GlyphVertex a{q.x0, q.y1, u0, v0, t.color}, b{q.x1, q.y1, u1, v0, t.color},
            c{q.x1, q.y0, u1, v1, t.color}, d{q.x0, q.y0, u0, v1, t.color};
        v.insert(v.end(), {a, b, c, a, c, d});
      }
    }
    use(text_, f);
    gl_.ActiveTexture(GL_TEXTURE0);
    gl_.BindVertexArray(vao_[2]);
    gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_[2]);
    for (const auto& [atlas, v] : batches) {
      if (v.empty()) continue;
      gl_.BindTexture(GL_TEXTURE_2D, texture(atlas));
      gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(GlyphVertex)),
                     v.data(), GL_STREAM_DRAW);
      gl_.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(v.size()));
    }
  }

  // any GL error so far becomes a RenderError
  void check(const char* when) {
    const std::string e = gl::error_name(gl_.GetError());
    if (!e.empty()) throw RenderError(std::string("OpenGL error during ") + when + ": " + e);
  }

  gl::OsMesaContext ctx_;
  Api gl_;
  FontProvider fonts_;
  Program polygon_, disk_, wall_, overlay_, text_;
  GLuint vao_[3] = {}, vbo_[3] = {};
  GLuint ms_fbo_ = 0, ms_rb_ = 0;  ///< the multisampled target (0: draw into framebuffer 0)
  int tw_ = 0, th_ = 0;            ///< its size, px
  int wanted_ = 0, samples_ = 1;   ///< samples asked for and obtained
  GLint max_samples_ = 1, max_size_ = 4096;
  std::map<const GlyphAtlas*, std::pair<std::shared_ptr<const GlyphAtlas>, GLuint>> textures_;
  std::string version_, device_;
};

}  // namespace

std::unique_ptr<Renderer> make_gl_renderer() { return std::make_unique<GlRenderer>(); }

}  // namespace gs
