// progress on the terminal: a bar with rate and ETA on a TTY, plain lines otherwise
#pragma once
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

namespace gs {

/// where and how often a Progress draws; the defaults are those of `run` and `sweep`
struct ProgressSettings {
  std::function<double()> clock;  ///< seconds since any fixed origin; empty: steady_clock
  int tty = -1;                   ///< 1: redraw one line in place, 0: plain lines; −1: isatty
  std::FILE* out = nullptr;       ///< nullptr: stderr
  double delay = 0.0;             ///< s: nothing is drawn before (work this short shows nothing)
  double log_every = 30.0;        ///< s between plain lines (not a terminal)
  double log_fraction = 0.1;      ///< a plain line also after this share of the work
};

class Progress {
 public:
  /// total: the amount of work (simulated seconds, steps, taps); unit names it
  Progress(std::string label, double total, std::string unit, bool quiet = false,
           ProgressSettings settings = {});
  /// report that `done` of total is finished (cheap to call often: it throttles itself); the
  /// ETA is the rate since the first call's `done`, so work resumed half done is not counted
  /// as done in no time
  void update(double done, const std::string& extra = "");
  /// `work` of the total was done in earlier sittings (a job resumed part done): the ETA's rate
  /// leaves it out
  void carried(double work) { carried_ += work; }
  /// the final line (none when nothing was drawn and the work took less than the delay)
  void finish(const std::string& summary);
  double elapsed() const;

 private:
  void draw(double done, const std::string& extra, bool final_line);
  double now() const;
  std::string label_, unit_;
  double total_;
  bool tty_, quiet_;
  ProgressSettings set_;
  std::FILE* out_;
  double start_, last_;
  double first_done_ = NAN;  ///< the work done at the first update: a resumed job's earlier share
  double carried_ = 0.0;     ///< work done in earlier sittings, as carried() reported it
  double last_fraction_ = -1.0;
  bool drawn_ = false;
};

/// "1h02m", "3m05s", "12.3s"
std::string format_duration(double seconds);

}  // namespace gs
