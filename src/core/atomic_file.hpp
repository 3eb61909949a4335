// whole small files written atomically (checkpoints, state files, JSON summaries): a reader
// sees the old file or the new one, never a half-written one
#pragma once
#include <string>

namespace gs {

/// write a whole small file atomically (temporary file, fsync, rename); OutputError naming the
/// path when it cannot be written
void write_file_atomic(const std::string& path, const std::string& contents);

}  // namespace gs
