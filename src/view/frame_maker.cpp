// FrameMaker: the [render] section's backend and frame settings around world_frame()
#include "view/frame_maker.hpp"

#include "core/error.hpp"

namespace gs {

FrameMaker::FrameMaker(const RenderSpec& r, const std::string& where) : spec_(r) {
  try {
    renderer_ = make_renderer(parse_renderer_kind(r.renderer));
  } catch (const RenderError& e) {
    throw InputError(where, "render.renderer",
                     std::string(e.what()) + " (use renderer = \"auto\" or \"software\")");
  }
}

Image FrameMaker::render(const World& w, const ContactSet* contacts, const FrameInfo& info) {
  const WorldFrame f = world_frame(w, contacts, info, spec_);
  return renderer_->render(build_frame(f.particles, f.walls, f.overlays, f.spec, f.box));
}

}  // namespace gs
