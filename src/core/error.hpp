// errors at the edges: every message names where it came from and what to do
#pragma once
#include <stdexcept>
#include <string>

namespace gs {

/// exit codes of the gransim command
enum ExitCode : int {
  kExitOk = 0,
  kExitFailure = 1,      ///< unexpected internal failure
  kExitBadInput = 2,     ///< bad scene, checkpoint, argument or path
  kExitUnstable = 3,     ///< a run-time health check failed
  kExitInterrupted = 4,  ///< stopped by a signal after writing a checkpoint
  kExitOutput = 5        ///< an output could not be written (disk full, unwritable)
};

/// bad user input: a scene key, a file, an argument. `where` is "file:line" or a path.
class InputError : public std::runtime_error {
 public:
  InputError(std::string where, std::string key, std::string what)
      : std::runtime_error(format(where, key, what)),
        where_(std::move(where)),
        key_(std::move(key)) {}
  const std::string& where() const { return where_; }
  const std::string& key() const { return key_; }

 private:
  static std::string format(const std::string& where, const std::string& key,
                            const std::string& what) {
    std::string s = where;
    if (!key.empty()) s += (s.empty() ? "" : ": ") + std::string("key '") + key + "'";
    if (!s.empty()) s += ": ";
    return s + what;
  }
  std::string where_;
  std::string key_;
};

/// an output file could not be written while a command ran (disk full, quota, removed
/// directory): the message names the file and the system's reason
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// a run-time health check failed (non-finite values, overlap, energy growth)
class HealthError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace gs
