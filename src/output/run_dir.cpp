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

void prepare_run_dir(const std::string& dir, bool force) {
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec))
      throw InputError(dir, "--out", "exists and is not a directory; choose another --out");
    bool empty = true;
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (e.path().filename() != ".lock") empty = false;
    if (!empty) {
      if (!force)
        throw InputError(dir, "--out",
                         "is not empty; refusing to overwrite a previous run (use --force, or "
                         "choose another --out)");
      for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename() != ".lock") fs::remove_all(e.path(), ec);
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
}

DirLock::DirLock(const std::string& dir, const std::string& what) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir, "", "cannot create the directory: " + ec.message());
  const std::string path = dir + "/.lock";
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

void write_file_atomic(const std::string& path, const std::string& contents) {
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw OutputError(path + ": cannot write: " + std::strerror(errno));
  std::size_t done = 0;
  while (done < contents.size()) {
    const ssize_t k = ::write(fd, contents.data() + done, contents.size() - done);
    if (k < 0) {
      const int e = errno;
      ::close(fd);
      ::unlink(tmp.c_str());
      throw OutputError(path + ": write failed: " + std::strerror(e));
    }
    done += static_cast<std::size_t>(k);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0 || std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int e = errno;
    ::unlink(tmp.c_str());
    throw OutputError(path + ": write failed: " + std::strerror(e));
  }
}

}  // namespace gs
