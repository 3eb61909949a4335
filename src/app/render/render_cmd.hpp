// `gransim render` (one saved state → PNG) and `gransim movie` (a run's frames or trajectory →
// MP4). cli.cpp adds them with one call and dispatches with another.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace gs {

/// drawing flags shared by `render` and `movie` (a trajectory is drawn frame by frame); each
/// one, when given, replaces the scene's [render] key
struct RenderFlags {
  std::string scene;              ///< scene file (default: scene.toml beside the input)
  std::vector<std::string> sets;  ///< --set overrides of the scene
  std::string color_by, colormap, size, range, camera, renderer, title;
  int msaa = 0;  ///< 0 = the scene's
  bool no_colorbar = false, chains = false, no_clock = false;
};

struct RenderCommandOptions {
  std::string input;  ///< run directory, state file, trajectory
  std::string out;    ///< PNG (default: DIR/frame.png, or the input's stem + .png)
  int frame = -1;     ///< trajectory frame (−1 = last)
  RenderFlags flags;
};

struct MovieCommandOptions {
  std::string input;          ///< run directory or trajectory file
  std::string out;            ///< MP4 (default: DIR/movie.mp4)
  std::string from = "auto";  ///< "frames", "trajectory" or "auto" (frames when there are any)
  int fps = 0, crf = -1;      ///< 0 / −1 = the scene's
  std::string preset;         ///< "" = the scene's
  bool force = false;         ///< replace an existing output file
  bool quiet = false;
  RenderFlags flags;
};

int render_command(const RenderCommandOptions& o);
int movie_command(const MovieCommandOptions& o);

/// the subcommands and their options, alive from add_render_commands to the dispatch
struct RenderCommands;
std::shared_ptr<RenderCommands> add_render_commands(CLI::App& app);
/// the exit code of render or movie when one of them was chosen, else nullopt
std::optional<int> dispatch_render_commands(const RenderCommands& rc);

}  // namespace gs
