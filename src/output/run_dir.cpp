#include "output/run_dir.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/error.hpp"

namespace fs = std::filesystem;

namespace gs {

void SetAside::discard() {
  if (dir_.empty()) return;
  std::error_code ec;
  fs::remove_all(fs::path(dir_) / kFolder, ec);
  dir_.clear();
}

void SetAside::restore() noexcept {
  if (dir_.empty()) return;
  try {
    const fs::path dir(dir_), aside = dir / kFolder;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      const fs::path name = e.path().filename();
      if (name != ".lock" && name != kFolder) fs::remove_all(e.path(), ec);
    }
    for (const auto& e : fs::directory_iterator(aside, ec))
      fs::rename(e.path(), dir / e.path().filename(), ec);
    fs::remove_all(aside, ec);
  } catch (...) {  // (a directory that vanished meanwhile: nothing left to put back)
  }
  dir_.clear();
}

SetAside prepare_run_dir(const std::string& dir, bool force) {
  std::error_code ec;
  SetAside aside;
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec))
      throw InputError(dir, "--out", "exists and is not a directory; choose another --out");
    // (files a killed earlier --force left aside belong to a run that was to be replaced)
    fs::remove_all(fs::path(dir) / SetAside::kFolder, ec);
    bool empty = true;
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (e.path().filename() != ".lock") empty = false;
    if (!empty) {
      if (!force)
        throw InputError(dir, "--out",
                         "is not empty; refusing to overwrite a previous run (use --force, or "
                         "choose another --out)");
      // set aside by renaming within the directory (one file system: nothing is copied)
      const fs::path folder = fs::path(dir) / SetAside::kFolder;
      fs::create_directory(folder, ec);
      if (ec) throw InputError(dir, "--out", "cannot set the old run aside: " + ec.message());
      aside = SetAside(dir);
      for (const auto& e : fs::directory_iterator(dir)) {
        const fs::path name = e.path().filename();
        if (name == ".lock" || name == SetAside::kFolder) continue;
        fs::rename(e.path(), folder / name, ec);
        if (ec) {
          aside.restore();
          throw InputError(e.path().string(), "--out",
                           "cannot set the old run's file aside: " + ec.message());
        }
      }
    }
  } else {
    fs::create_directories(dir, ec);
    if (ec) throw InputError(dir, "--out", "cannot create directory: " + ec.message());
  }
  // probe that we can write here before any work is done
  const std::string probe = dir + "/.gransim-write-test";
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw InputError(dir, "--out", std::string("cannot write: ") + std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
  return aside;
}

DirLock::DirLock(const std::string& dir, const std::string& what) : DirLock(dir, what, ".lock") {}

DirLock::DirLock(const std::string& dir, const std::string& what, const std::string& name) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir, "", "cannot create the directory: " + ec.message());
  const std::string path = dir + "/" + name;
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw InputError(dir, "", std::string("cannot write: ") + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int e = errno;
    char pid[32] = {0};
    const ssize_t n = ::pread(fd_, pid, sizeof pid - 1, 0);
    ::close(fd_);
    fd_ = -1;
    if (e == EWOULDBLOCK) {
      std::string holder = n > 0 ? std::string(pid, static_cast<std::size_t>(n)) : "";
      while (!holder.empty() && (holder.back() == '\n' || holder.back() == ' ')) holder.pop_back();
      throw InputError(dir, "",
                       "another gransim process (PID " + (holder.empty() ? "unknown" : holder) +
                           ") is writing here; " + what +
                           " refused (wait for it to finish, or choose another directory)");
    }
    throw InputError(dir, "", std::string("cannot lock: ") + std::strerror(e));
  }
  const std::string me = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, me.data(), me.size(), 0) < 0) {
    // the lock holds without the PID; a refused writer then says "PID unknown"
  }
}

DirLock::~DirLock() {
  if (fd_ >= 0) ::close(fd_);  // closing the descriptor releases the lock
}

namespace {

bool is_run_dir(const fs::path& d) {
  std::error_code ec;
  return !d.empty() && (fs::exists(d / "run.json", ec) || fs::exists(d / "scene.toml", ec) ||
                        fs::exists(d / ".lock", ec));
}

// the same file, whether or not it exists yet (weakly canonical: symlinks and ".." resolved)
bool same_path(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  const fs::path ca = fs::weakly_canonical(fs::absolute(a), ec);
  const fs::path cb = fs::weakly_canonical(fs::absolute(b), ec);
  return ca == cb;
}

}  // namespace

std::string run_dir_of(const std::string& file) {
  std::error_code ec;
  const fs::path parent = fs::weakly_canonical(fs::absolute(fs::path(file)), ec).parent_path();
  if (is_run_dir(parent)) return parent.string();
  if (parent.filename() == "frames" && is_run_dir(parent.parent_path()))
    return parent.parent_path().string();
  return "";
}

void check_output_file(const std::string& out, const std::vector<std::string>& inputs,
                       const std::string& flag,
                       const std::function<bool(const std::filesystem::path&)>& own) {
  std::error_code ec;
  for (const std::string& in : inputs)
    if (!in.empty() && same_path(out, in))
      throw InputError(out, flag, "is an input of this command; choose another " + flag);
  if (fs::is_directory(out, ec))
    throw InputError(out, flag, "is a folder; " + flag + " names the output file");
  const std::string run = run_dir_of(out);
  if (run.empty() || !fs::exists(out, ec)) return;
  if (own(fs::path(out))) return;
  throw InputError(out, flag, "is a file of the run in " + run + "; choose another " + flag);
}

}  // namespace gs
