// trajectory export as extended XYZ (one frame after another in one text file), in the
// columns ASE and OVITO map to their own (docs/rendering.md): per particle an element-like
// symbol, position, species name and index, label, velocity, radius, orientation, angular
// velocity, speed, number of sides and contacts, with the box, time, step, gravity and tap in
// each frame's comment line. The reader takes these columns and the older set alike.
#pragma once
#include <cstdint>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "contact/contact_set.hpp"
#include "core/vec.hpp"
#include "world/world.hpp"

namespace gs {

/// the columns written, as the Properties= key of the comment line. `species` holds a chemical
/// symbol (ASE takes it for one, OVITO for the Particle Type), `name` the species' name;
/// `omega` is the vector (0, 0, ω), OVITO's Angular Velocity
inline constexpr const char* kTrajectoryProperties =
    "species:S:1:pos:R:3:name:S:1:species_index:I:1:id:I:1:velo:R:3:radius:R:1:theta:R:1:"
    "orientation:R:4:omega:R:3:speed:R:1:sides:I:1:contacts:I:1";

/// the symbol in the `species` column for species index k: the element with Z = k + 1
/// (H, He, Li …, repeating after 118)
std::string_view species_symbol(std::size_t k);
/// a species name as one whitespace-free token of the `name` column (blanks become '_')
std::string name_token(const std::string& name);

/// append one frame of the world to `out` (positions as stored: periodic boxes unwrapped up to
/// the engine's ±32 box lengths); `contacts` gives the contacts column (null: zeros)
void write_trajectory_frame(std::ostream& out, const World& w, const ContactSet* contacts,
                            Vec2 gravity, std::optional<long> tap);

/// one frame read back
struct TrajectoryFrame {
  double time = 0.0;  ///< s
  std::int64_t step = 0;
  std::optional<Vec2> gravity;      ///< m/s², when recorded
  std::optional<long> tap;          ///< when recorded
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
