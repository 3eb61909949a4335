// run directories: created fresh, never overwritten without --force
#pragma once
#include <string>

namespace gs {

/// make `dir` ready for a new run: create it, or accept it if empty; a non-empty directory is
/// refused (InputError) unless force, in which case its contents are removed
void prepare_run_dir(const std::string& dir, bool force);
/// write a whole small file atomically (temporary file, fsync, rename)
void write_file_atomic(const std::string& path, const std::string& contents);

}  // namespace gs
