#include "core/input_file.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "core/error.hpp"

namespace gs {

void check_input_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int e = errno;
    throw InputError(
        path, "",
        e == ENOENT ? "no such file" : "cannot read the " + what + ": " + std::strerror(e));
  }
  if (S_ISDIR(st.st_mode)) throw InputError(path, "", "is a directory, not a " + what);
  if (!S_ISREG(st.st_mode)) {
    const char* kind = S_ISFIFO(st.st_mode)   ? "a FIFO (named pipe)"
                       : S_ISCHR(st.st_mode)  ? "a character device"
                       : S_ISBLK(st.st_mode)  ? "a block device"
                       : S_ISSOCK(st.st_mode) ? "a socket"
                                              : "not a regular file";
    throw InputError(path, "",
                     std::string("is ") + kind + ", not a " + what +
                         " (gransim reads inputs only from regular files)");
  }
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes)
    throw InputError(path, "",
                     "is " + std::to_string(st.st_size >> 20) + " MiB, larger than the " +
                         std::to_string(max_bytes >> 20) + " MiB a " + what + " may have");
}

}  // namespace gs
