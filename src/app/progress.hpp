// progress on the terminal: a bar with rate and ETA on a TTY, plain lines otherwise
#pragma once
#include <chrono>
#include <string>

namespace gs {

class Progress {
 public:
  /// total: the amount of work (simulated seconds, steps, taps); unit names it
  Progress(std::string label, double total, std::string unit, bool quiet = false);
  /// report that `done` of total is finished (cheap to call often: it throttles itself)
  void update(double done, const std::string& extra = "");
  /// the final line
  void finish(const std::string& summary);
  double elapsed() const;

 private:
  void draw(double done, const std::string& extra, bool final_line);
  std::string label_, unit_;
  double total_;
  bool tty_, quiet_;
  std::chrono::steady_clock::time_point start_, last_;
  double last_fraction_ = -1.0;
};

/// "1h02m", "3m05s", "12.3s"
std::string format_duration(double seconds);

}  // namespace gs
