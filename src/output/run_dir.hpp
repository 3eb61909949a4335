// run directories: created fresh, never overwritten without --force
#pragma once
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/atomic_file.hpp"  // write_file_atomic, for the run directory's summaries

namespace gs {

/// a previous run's files set aside in DIR/.gransim-replaced while a new run (--force) proves
/// itself: discarded once it has passed its first health check, restored if it fails before
class SetAside {
 public:
  SetAside() = default;
  explicit SetAside(std::string dir) : dir_(std::move(dir)) {}
  SetAside(SetAside&& o) noexcept : dir_(std::exchange(o.dir_, {})) {}
  SetAside& operator=(SetAside&& o) noexcept {
    restore();
    dir_ = std::exchange(o.dir_, {});
    return *this;
  }
  SetAside(const SetAside&) = delete;
  /// neither discarded nor restored (an error on the way): the old files are put back
  ~SetAside() { restore(); }
  /// are files set aside?
  bool holds() const { return !dir_.empty(); }
  /// the new run is sound: the old files are deleted
  void discard();
  /// the new run failed: its files are deleted and the old ones put back where they were
  void restore() noexcept;
  /// the folder the old files wait in
  static constexpr const char* kFolder = ".gransim-replaced";

 private:
  std::string dir_;  ///< the run directory ("" when nothing is set aside)
};

/// make `dir` ready for a new run: create it, or accept it if empty; a non-empty directory is
/// refused (InputError) unless force, in which case its contents (all but the directory's
/// .lock, which the caller may hold) are set aside, not yet deleted
[[nodiscard]] SetAside prepare_run_dir(const std::string& dir, bool force);
/// one writer per directory: an advisory lock (flock) on DIR/.lock, held while the object
/// lives; the kernel releases it when the process ends, however it ends (kill -9 leaves no
/// stale lock). The holder writes its PID into the file so that a refused writer can name it.
class DirLock {
 public:
  /// creates DIR if needed and takes the lock; throws InputError naming DIR and the holder's
  /// PID when another process holds it (`what` says what wanted it: "run", "sweep", …)
  DirLock(const std::string& dir, const std::string& what);
  /// the same with another lock file in DIR (`name`), for a second writer of one directory
  DirLock(const std::string& dir, const std::string& what, const std::string& name);
  ~DirLock();
  DirLock(const DirLock&) = delete;
  DirLock& operator=(const DirLock&) = delete;

 private:
  int fd_ = -1;
};

/// the run directory a file lies in: its folder, or the folder above (a run's frames/), when
/// that holds run.json, scene.toml or .lock; "" otherwise
std::string run_dir_of(const std::string& file);

/// an output file must not be one of the command's inputs, nor an existing file of a run other
/// than one the command itself may replace (`own(path)`: e.g. a PNG outside frames/ that is not
/// final.png): InputError naming `flag` otherwise
void check_output_file(const std::string& out, const std::vector<std::string>& inputs,
                       const std::string& flag,
                       const std::function<bool(const std::filesystem::path&)>& own);

}  // namespace gs
