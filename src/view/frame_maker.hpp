// a renderer with the [render] settings: World (+ contacts) → Image, with the backend the
// scene names (OSMesa where it was compiled in and works, else the software rasteriser)
#pragma once
#include <memory>
#include <string>

#include "core/image.hpp"
#include "render/renderer.hpp"
#include "scene/spec.hpp"
#include "view/render_world.hpp"

namespace gs {

/// a renderer with the [render] settings: World (+ contacts) → Image
class FrameMaker {
 public:
  /// starts the backend named by r.renderer; InputError naming `where` and render.renderer
  /// when it cannot (e.g. "gl" without a working OSMesa)
  FrameMaker(const RenderSpec& r, const std::string& where);
  /// draw one frame (contacts may be null unless needs_contacts(spec()))
  Image render(const World& w, const ContactSet* contacts, const FrameInfo& info);
  const RenderSpec& spec() const { return spec_; }
  std::string describe() const { return renderer_->describe(); }

 private:
  RenderSpec spec_;
  std::unique_ptr<Renderer> renderer_;
};

}  // namespace gs
