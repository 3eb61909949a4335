// run directories: created fresh, never overwritten without --force
#pragma once
#include <string>

namespace gs {

/// make `dir` ready for a new run: create it, or accept it if empty; a non-empty directory is
/// refused (InputError) unless force, in which case its contents are removed (all but the
/// directory's .lock, which the caller may hold)
void prepare_run_dir(const std::string& dir, bool force);
/// one writer per directory: an advisory lock (flock) on DIR/.lock, held while the object
/// lives; the kernel releases it when the process ends, however it ends (kill -9 leaves no
/// stale lock). The holder writes its PID into the file so that a refused writer can name it.
class DirLock {
 public:
  /// creates DIR if needed and takes the lock; throws InputError naming DIR and the holder's
  /// PID when another process holds it (`what` says what wanted it: "run", "sweep", …)
  DirLock(const std::string& dir, const std::string& what);
  ~DirLock();
  DirLock(const DirLock&) = delete;
  DirLock& operator=(const DirLock&) = delete;

 private:
  int fd_ = -1;
};

/// write a whole small file atomically (temporary file, fsync, rename)
void write_file_atomic(const std::string& path, const std::string& contents);

}  // namespace gs
