// the [render] observers of a run: the frame recorder (PNG frames and/or an MP4 encoded in
// process while the simulation runs) and the trajectory writers (extended XYZ, H5MD)
#pragma once
#include <memory>
#include <string>

#include "core/image.hpp"
#include "render/renderer.hpp"
#include "scene/spec.hpp"
#include "sim/observer.hpp"
#include "view/frame_maker.hpp"

namespace gs {

/// is a movie encoder compiled in (FFmpeg)?
bool movie_encoder_available();

/// append the observers the scene's [render] section asks for (none when it asks for
/// nothing); InputError when it asks for a movie in a build without FFmpeg
void add_render_observers(const SceneSpec& scene, Observers& observers);

/// the H5MD trajectory of a run: DIR/trajectory.h5md
inline constexpr const char* kH5mdTrajectoryFile = "trajectory.h5md";

/// frames.csv columns: frame index, time, step, tap (−1 none), gravity
inline constexpr const char* kFrameIndexFile = "frames.csv";

/// name of frame k in DIR/frames/: frame_000123.png
std::string frame_file_name(int k);

}  // namespace gs
