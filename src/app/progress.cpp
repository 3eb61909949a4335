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

Progress::Progress(std::string label, double total, std::string unit, bool quiet)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      total_(total),
      tty_(::isatty(2) != 0),
      quiet_(quiet),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

double Progress::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::update(double done, const std::string& extra) {
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_).count();
  const double frac = total_ > 0 ? done / total_ : 0.0;
  // a TTY redraws a few times a second; a log gets a line every 10% or every 30 s
  const bool due = tty_ ? since > 0.2 : (frac - last_fraction_ >= 0.1 || since > 30.0);
  if (!due) return;
  last_ = now;
  last_fraction_ = frac;
  draw(done, extra, false);
}

void Progress::draw(double done, const std::string& extra, bool final_line) {
  const double el = elapsed();
  const double frac = std::clamp(total_ > 0 ? done / total_ : 1.0, 0.0, 1.0);
  const double eta = frac > 0 ? el * (1.0 - frac) / frac : NAN;
  char head[160];
  std::snprintf(head, sizeof head, "%s %5.1f%% (%.4g/%.4g %s) elapsed %s ETA %s", label_.c_str(),
                100.0 * frac, done, total_, unit_.c_str(), format_duration(el).c_str(),
                final_line ? "0s" : format_duration(eta).c_str());
  if (tty_) {
    const int width = 24, fill = static_cast<int>(frac * width);
    std::string bar = "[" + std::string(fill, '#') + std::string(width - fill, '.') + "] ";
    std::fprintf(stderr, "\r\033[K%s%s %s", bar.c_str(), head, extra.c_str());
    if (final_line) std::fputc('\n', stderr);
  } else {
    std::fprintf(stderr, "%s %s\n", head, extra.c_str());
  }
  std::fflush(stderr);
}

void Progress::finish(const std::string& summary) {
  if (quiet_) return;
  draw(total_, summary, true);
}

}  // namespace gs
