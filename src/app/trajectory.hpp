// trajectory export as extended XYZ (one frame after another in one text file; OVITO, ASE and
// VMD read it): per particle species, position, velocity, radius, orientation, angular
// velocity, speed and number of sides, with the box, time, step, gravity and tap in each
// frame's comment line
#pragma once
#include <cstdint>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "core/vec.hpp"
#include "world/world.hpp"

namespace gs {

/// the columns written, as the Properties= key of the comment line
inline constexpr const char* kTrajectoryProperties =
    "species:S:1:pos:R:3:velo:R:3:radius:R:1:theta:R:1:omega:R:1:speed:R:1:sides:I:1";

/// append one frame of the world to `out` (positions as stored: periodic boxes unwrapped up to
/// the engine's ±32 box lengths)
void write_trajectory_frame(std::ostream& out, const World& w, Vec2 gravity,
                            std::optional<long> tap);

/// one frame read back
struct TrajectoryFrame {
  double time = 0.0;              ///< s
  std::int64_t step = 0;
  std::optional<Vec2> gravity;    ///< m/s², when recorded
  std::optional<long> tap;        ///< when recorded
  std::array<double, 2> lattice{};  ///< box lengths from Lattice=, m
  std::vector<std::string> species;
  std::vector<double> x, y, vx, vy, radius, theta, omega, speed;  ///< SI
  std::vector<int> sides;
  std::size_t size() const { return x.size(); }
};

/// reads frames one after another; errors are InputError naming file and line
class TrajectoryReader {
 public:
  explicit TrajectoryReader(const std::string& path);
  /// the next frame, false at the end of the file
  bool next(TrajectoryFrame& f);
  /// frames read so far
  int frames() const { return frames_; }

 private:
  [[noreturn]] void fail(const std::string& what) const;
  std::string path_;
  std::ifstream in_;
  long line_ = 0;
  int frames_ = 0;
};

/// replace the particles of `w` (built from the trajectory's scene) with the frame's
/// (species by name); InputError naming `where` on a species the scene does not know
void load_trajectory_frame(World& w, const TrajectoryFrame& f, const std::string& where);

}  // namespace gs
