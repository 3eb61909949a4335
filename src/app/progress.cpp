#include "app/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace gs {

std::string format_duration(double s) {
  char buf[32];
  if (!std::isfinite(s) || s < 0) return "--";
  if (s < 60) {
    std::snprintf(buf, sizeof buf, "%.1fs", s);
  } else if (s < 3600) {
    std::snprintf(buf, sizeof buf, "%dm%02ds", static_cast<int>(s / 60), static_cast<int>(s) % 60);
  } else {
    std::snprintf(buf, sizeof buf, "%dh%02dm", static_cast<int>(s / 3600),
                  static_cast<int>(s / 60) % 60);
  }
  return buf;
}

Progress::Progress(std::string label, double total, std::string unit, bool quiet,
                   ProgressSettings settings)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      total_(total),
      tty_(settings.tty < 0 ? ::isatty(2) != 0 : settings.tty != 0),
      quiet_(quiet),
      set_(std::move(settings)),
      out_(set_.out ? set_.out : stderr),
      start_(now()),
      last_(start_) {}

double Progress::now() const {
  if (set_.clock) return set_.clock();
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double Progress::elapsed() const { return now() - start_; }

void Progress::update(double done, const std::string& extra) {
  if (std::isnan(first_done_)) first_done_ = done;
  if (quiet_) return;
  const double t = now();
  if (t - start_ < set_.delay) return;
  const double since = t - last_;
  const double frac = total_ > 0 ? done / total_ : 0.0;
  // a TTY redraws a few times a second; a log gets a line every log_fraction or log_every s
  const bool due =
      !drawn_ || (tty_ ? since > 0.2
                       : (frac - last_fraction_ >= set_.log_fraction || since >= set_.log_every));
  if (!due) return;
  last_ = t;
  last_fraction_ = frac;
  draw(done, extra, false);
}

void Progress::draw(double done, const std::string& extra, bool final_line) {
  const double el = elapsed();
  const double frac = std::clamp(total_ > 0 ? done / total_ : 1.0, 0.0, 1.0);
  // the rate of this sitting: work resumed part done says nothing of how fast the rest goes
  const double base =
      std::min(std::max(std::isnan(first_done_) ? 0.0 : first_done_, carried_), done);
  const double rate = el > 0 && done > base ? (done - base) / el : 0.0;
  const double eta = rate > 0 ? std::max(total_ - done, 0.0) / rate : NAN;
  char head[160];
  std::snprintf(head, sizeof head, "%s %5.1f%% (%.4g/%.4g %s) elapsed %s ETA %s", label_.c_str(),
                100.0 * frac, done, total_, unit_.c_str(), format_duration(el).c_str(),
                final_line ? "0s" : format_duration(eta).c_str());
  if (tty_) {
    const int width = 24, fill = static_cast<int>(frac * width);
    std::string bar = "[" + std::string(fill, '#') + std::string(width - fill, '.') + "] ";
    std::fprintf(out_, "\r\033[K%s%s %s", bar.c_str(), head, extra.c_str());
    if (final_line) std::fputc('\n', out_);
  } else {
    std::fprintf(out_, "%s %s\n", head, extra.c_str());
  }
  std::fflush(out_);
  drawn_ = true;
}

void Progress::finish(const std::string& summary) {
  if (quiet_ || (!drawn_ && elapsed() < set_.delay)) return;
  draw(total_, summary, true);
}

}  // namespace gs
