// the [output.snapshots] table of a scene: when configurations are written and in which formats
// (SnapshotSpec lives in spec.hpp); read and written for parse.cpp / write.cpp
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "scene/spec.hpp"

namespace gs::scene_detail {

struct Ctx;
class TableReader;

/// read [output.snapshots] from the [output] table (after [drive]: at_taps needs a tapping drive)
void read_snapshots(const TableReader& output, SceneSpec& s);
/// its keys and TOML values in the order scene_to_toml writes them
std::vector<std::pair<std::string, std::string>> snapshot_entries(const SnapshotSpec& o);

}  // namespace gs::scene_detail
