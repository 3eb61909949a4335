// inputs are read only from regular files of bounded size: a FIFO would block, /dev/zero or a
// huge file would never end or exhaust memory
#pragma once
#include <cstdint>
#include <string>

namespace gs {

/// the largest input file gransim reads (scenes, CSV series, state files, checkpoints)
inline constexpr std::uintmax_t kMaxInputBytes = std::uintmax_t{4} << 30;
/// the largest scene file (a scene is text a person writes; even explicit particles fit)
inline constexpr std::uintmax_t kMaxSceneBytes = std::uintmax_t{256} << 20;

/// throws InputError naming `path` unless it is a regular file (after symlinks) of at most
/// `max_bytes`; `what` names the kind of file in the message ("scene file", "state file", …).
/// stat() does not open the file, so a FIFO without a writer cannot block here.
void check_input_file(const std::string& path, const std::string& what,
                      std::uintmax_t max_bytes = kMaxInputBytes);

}  // namespace gs
