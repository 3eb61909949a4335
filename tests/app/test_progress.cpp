// the progress display with an injected clock: nothing for short work, one line redrawn in place
// on a terminal, a plain line every few seconds otherwise, nothing when quiet; and `analyze`
// shows it for an analysis that takes a while
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "app/analyze/analyze.hpp"
#include "app/progress.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;

// a stream that collects what is written to it
struct Captured {
  char* buf = nullptr;
  std::size_t len = 0;
  std::FILE* f = open_memstream(&buf, &len);
  std::string text() {
    std::fflush(f);
    return std::string(buf, len);
  }
  ~Captured() {
    std::fclose(f);
    std::free(buf);
  }
};

int count(const std::string& s, const std::string& what) {
  int n = 0;
  for (auto p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

TEST(Progress, PlainLinesEveryFewSecondsAfterTheDelay) {
  Captured out;
  double now = 100.0;
  Progress p("analyze", 10, "steps", false, {[&] { return now; }, 0, out.f, 2.0, 5.0, 2.0});
  for (int i = 1; i <= 10; ++i) {
    now += 1.0;  // one second a step: lines at 2 s (the first after the delay), 7 s
    p.update(i);
  }
  EXPECT_EQ(count(out.text(), "\n"), 2) << out.text();
  EXPECT_NE(out.text().find("analyze  20.0% (2/10 steps)"), std::string::npos) << out.text();
  EXPECT_NE(out.text().find("analyze  70.0% (7/10 steps)"), std::string::npos) << out.text();
  p.finish("done");
  EXPECT_EQ(count(out.text(), "\n"), 3);
  EXPECT_NE(out.text().find("100.0%"), std::string::npos);
  EXPECT_EQ(out.text().find('\r'), std::string::npos);  // a log gets no control characters
}

TEST(Progress, OneLineRewrittenOnATerminal) {
  Captured out;
  double now = 0.0;
  Progress p("analyze", 100, "steps", false, {[&] { return now; }, 1, out.f, 2.0, 5.0, 2.0});
  for (int i = 1; i <= 100; ++i) {
    now += 0.1;
    p.update(i);
  }
  const std::string s = out.text();
  EXPECT_GT(count(s, "\r\033[K"), 10) << s;  // redrawn several times a second of its clock
  EXPECT_EQ(count(s, "\n"), 0);              // in place
  p.finish("done");
  EXPECT_EQ(count(out.text(), "\n"), 1);
}

// work resumed half done: the ETA comes from this sitting's rate (1 unit a second), not from
// the half that was done before it started (which would say 10 s instead of 40 s)
TEST(Progress, ResumedWorkTakesItsRateFromThisSitting) {
  Captured out;
  double now = 0.0;
  Progress p("sweep", 100, "s", false, {[&] { return now; }, 0, out.f, 0.0, 5.0, 0.5});
  p.update(50);  // the first look: half was done in earlier sittings
  now = 10.0;
  p.update(60);
  EXPECT_NE(out.text().find("sweep  60.0% (60/100 s) elapsed 10.0s ETA 40.0s"), std::string::npos)
      << out.text();
}

// a sweep learns what its resumed runs did before only as it starts them: carried() work is
// left out of the rate as well
TEST(Progress, CarriedWorkIsLeftOutOfTheRate) {
  Captured out;
  double now = 0.0;
  Progress p("sweep", 100, "s", false, {[&] { return now; }, 0, out.f, 0.0, 5.0, 0.5});
  p.update(0);
  p.carried(50);  // a run resumed with half the work behind it
  now = 10.0;
  p.update(60);
  EXPECT_NE(out.text().find("ETA 40.0s"), std::string::npos) << out.text();
}

TEST(Progress, NothingForShortWorkOrWhenQuiet) {
  for (bool quiet : {false, true}) {
    Captured out;
    double now = 0.0;
    const double step = quiet ? 10.0 : 0.1;  // quiet: long work, still nothing
    Progress p("analyze", 10, "steps", quiet, {[&] { return now; }, 0, out.f, 2.0, 5.0, 2.0});
    for (int i = 1; i <= 10; ++i) {
      now += step;
      p.update(i);
    }
    p.finish("done");
    EXPECT_EQ(out.text(), "") << quiet;
  }
}

// `analyze` on two plain series, its clock a second a call: the display appears, and -q
// silences it
TEST(Progress, AnalyzeShowsItsProgress) {
  const fs::path dir = fs::temp_directory_path() / ("gs-progress-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 0.002);
  for (const char* name : {"a.csv", "b.csv"}) {
    std::ofstream f(dir / name);
    f << "phi\n";
    for (int i = 0; i < 400; ++i) f << 0.82 + noise(rng) << "\n";
  }
  for (bool quiet : {false, true}) {
    Captured out;
    double now = 0.0;
    AnalyzeOptions o;
    o.dirs = {(dir / "a.csv").string(), (dir / "b.csv").string()};
    o.out = (dir / (quiet ? "quiet" : "shown")).string();
    o.test_area = 0.01;
    o.charts = false;
    o.quiet = quiet;
    o.progress.clock = [&] { return now += 1.0; };
    o.progress.tty = 0;
    o.progress.out = out.f;
    ASSERT_EQ(analyze_command(o), 0);
    const std::string s = out.text();
    if (quiet) {
      EXPECT_EQ(s, "");
    } else {
      EXPECT_GE(count(s, "analyze "), 3) << s;  // a line every 5 s of its clock, and the last
      EXPECT_NE(s.find("100.0%"), std::string::npos) << s;
      EXPECT_NE(s.find("2 runs, 800 taps"), std::string::npos) << s;
    }
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace gs
