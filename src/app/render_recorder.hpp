// the [render] observers of a run: the frame recorder (PNG frames and/or an MP4 encoded in
// process while the simulation runs) and the trajectory writer (extended XYZ)
#pragma once
#include <memory>
#include <string>

#include "app/render_world.hpp"
#include "core/image.hpp"
#include "render/renderer.hpp"
#include "scene/spec.hpp"
#include "sim/observer.hpp"

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

/// is a movie encoder compiled in (FFmpeg)?
bool movie_encoder_available();

/// append the observers the scene's [render] section asks for (none when it asks for
/// nothing); InputError when it asks for a movie in a build without FFmpeg
void add_render_observers(const SceneSpec& scene, Observers& observers);

/// frames.csv columns: frame index, time, step, tap (−1 none), gravity
inline constexpr const char* kFrameIndexFile = "frames.csv";

/// name of frame k in DIR/frames/: frame_000123.png
std::string frame_file_name(int k);

}  // namespace gs
