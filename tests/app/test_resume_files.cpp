// a resume checks and truncates only the files a run appends to: the writer's lock (its PID
// text is longer or shorter from one writer to the next) and the final picture (rewritten at
// every stop) may shrink between sittings without costing the checkpoint
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;
using testing::Launch;
using testing::run_binary;

TEST(ResumeFiles, LockAndFinalPictureMayShrinkBetweenSittings) {
  const fs::path tmp =
      fs::temp_directory_path() / ("gs-resume-files-" + std::to_string(::getpid()));
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  const fs::path dir = tmp / "run";
  Launch stop;
  stop.alarm_s = 120;
  stop.signal = SIGINT;
  // each sitting is stopped once it has written a checkpoint (an event, not a moment)
  stop.signal_when = testing::new_checkpoint_in(dir);
  // the demo records a movie and draws final.png at every stop; checkpoints every 500 steps
  const auto first = run_binary({"run", std::string(GS_SOURCE_DIR) + "/scenes/demo.toml", "--out",
                                 dir.string(), "-q", "--set", "scene.duration=60", "--set",
                                 "output.checkpoint_steps=500", "--set", "render.size=[160, 256]"},
                                tmp / "first.log", stop);
  ASSERT_EQ(first.code, 4) << first.output;
  ASSERT_TRUE(fs::exists(dir / "final.png"));
  // a longer PID in the lock, then a second sitting that checkpoints with it
  std::ofstream(dir / ".lock") << "123456789\n";
  stop.signal_when = testing::new_checkpoint_in(dir);
  const auto second = run_binary({"resume", dir.string(), "-q"}, tmp / "second.log", stop);
  ASSERT_EQ(second.code, 4) << second.output;
  // the next writer's PID is shorter, the picture smaller: the resume goes on regardless
  std::ofstream(dir / ".lock") << "1\n";
  std::ofstream(dir / "final.png") << "x";
  stop.signal_when = testing::new_checkpoint_in(dir);
  const auto third = run_binary({"resume", dir.string(), "-q"}, tmp / "third.log", stop);
  EXPECT_EQ(third.code, 4) << third.output;
  EXPECT_EQ(third.output.find("skipping"), std::string::npos) << third.output;
  fs::remove_all(tmp);
}

}  // namespace
}  // namespace gs
