// the [rfm] section of a scene: the Random Force Model measurements (docs/physics.md §5.3). RfmSpec
// itself lives in spec.hpp; this reads and writes it for parse.cpp / write.cpp.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "scene/spec.hpp"

namespace gs::scene_detail {

struct Ctx;
class TableReader;

/// read [rfm] (after [box], [drive] and [species]: defaults follow the drive kind)
void read_rfm(const Ctx& ctx, const TableReader& top, SceneSpec& s);
/// the [rfm] keys and their TOML values in the order scene_to_toml writes them
std::vector<std::pair<std::string, std::string>> rfm_entries(const RfmSpec& r);
/// is the [rfm] block written? (for random-force scenes and whenever the file had one, so
/// other scenes keep their key list)
bool rfm_written(const SceneSpec& s);

}  // namespace gs::scene_detail
