// preparation.from_state: a run started from a checkpoint ends bitwise where the run that
// wrote it ends (Gear 6: history and contact springs taken); the same from a run directory, a
// relative path and the resolved scene in the fork's run directory; mismatches name file,
// line and key
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;
using testing::run_binary;
using testing::slurp;

// 30 decagons falling into a 0.1 m box under constant gravity, Gear 6
const char* kPile = R"(
[scene]
name = "pile"
duration = 0.5
[[material]]
name = "grain"
[[species]]
name = "big"
radius = 0.009
count = 15
[[species]]
name = "small"
radius = 0.00636
count = 15
[box]
width = 0.1
[preparation]
seed = 3
[integrator]
kind = "gear6"
dt = 5e-5
[drive]
kind = "gravity"
[output]
checkpoint_minutes = 0
checkpoint_steps = 5000
)";

class FromState : public ::testing::Test {
 protected:
  // one folder per test: ctest runs the tests of this file side by side
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           (std::string("gs_from_state_") +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "pile.toml") << kPile;
    const auto o = run({"run", (dir_ / "pile.toml").string(), "--out", (dir_ / "ref").string()});
    ASSERT_EQ(o.code, 0) << o.output;
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  static testing::Outcome run(std::vector<std::string> args) {
    args.push_back("--quiet");
    testing::Launch how;
    how.env = {"OMP_NUM_THREADS=1"};
    return run_binary(args, dir_ / "log.txt", how);
  }
  static fs::path dir_;
};
fs::path FromState::dir_;

TEST_F(FromState, CheckpointForkContinuesBitwise) {
  const fs::path ck = dir_ / "ref" / "checkpoint-000000005000.gsck";
  ASSERT_TRUE(fs::exists(ck));
  // half the run from the checkpoint half-way: the same grains, bit for bit
  const auto o =
      run({"run", (dir_ / "pile.toml").string(), "--out", (dir_ / "fork").string(), "--set",
           "preparation.from_state=" + ck.string(), "--set", "scene.duration=0.25"});
  ASSERT_EQ(o.code, 0) << o.output;
  EXPECT_EQ(slurp(dir_ / "fork" / "state.csv"), slurp(dir_ / "ref" / "state.csv"));
  // the resolved scene names the state by an absolute path and runs as it is
  const std::string resolved = slurp(dir_ / "fork" / "scene.toml");
  EXPECT_NE(resolved.find("from_state = \"" + ck.string() + "\""), std::string::npos) << resolved;
  const auto again =
      run({"run", (dir_ / "fork" / "scene.toml").string(), "--out", (dir_ / "again").string()});
  ASSERT_EQ(again.code, 0) << again.output;
  EXPECT_EQ(slurp(dir_ / "again" / "state.csv"), slurp(dir_ / "ref" / "state.csv"));
}

TEST_F(FromState, RunDirectoryRelativePathAndCountsLeftOut) {
  // a run directory whose newest checkpoint is the half-way one, named relative to the scene
  fs::create_directories(dir_ / "sub" / "half");
  fs::copy_file(dir_ / "ref" / "checkpoint-000000005000.gsck",
                dir_ / "sub" / "half" / "checkpoint-000000005000.gsck",
                fs::copy_options::overwrite_existing);
  std::string text = kPile;
  for (const char* c : {"count = 15\n", "count = 15\n"})
    text.erase(text.find(c), std::string(c).size());
  text.replace(text.find("seed = 3"), 8, "from_state = \"half\"");
  text.replace(text.find("duration = 0.5"), 14, "duration = 0.25");
  std::ofstream(dir_ / "sub" / "fork.toml") << text;
  const auto o =
      run({"run", (dir_ / "sub" / "fork.toml").string(), "--out", (dir_ / "fork_dir").string()});
  ASSERT_EQ(o.code, 0) << o.output;
  EXPECT_EQ(slurp(dir_ / "fork_dir" / "state.csv"), slurp(dir_ / "ref" / "state.csv"));
  EXPECT_NE(slurp(dir_ / "fork_dir" / "scene.toml").find("count = 15"), std::string::npos);
}

TEST_F(FromState, StateFileStartsWithoutHistory) {
  // a state file carries grains only: the run starts from them (and differs from the
  // checkpoint fork, which has the contact springs and Gear 6's history)
  const auto o = run({"run", (dir_ / "pile.toml").string(), "--out", (dir_ / "from_csv").string(),
                      "--set", "preparation.from_state=" + (dir_ / "ref" / "state.csv").string(),
                      "--set", "scene.duration=0.01"});
  ASSERT_EQ(o.code, 0) << o.output;
  const std::string s = slurp(dir_ / "from_csv" / "state.csv");
  EXPECT_EQ(std::count(s.begin(), s.end(), '\n'), 31);
}

TEST_F(FromState, MismatchesNameFileLineAndKey) {
  const std::string state = (dir_ / "ref" / "state.csv").string();
  struct Bad {
    std::string name, from, to, want;
  };
  const std::vector<Bad> bad = {
      {"species.toml", "name = \"small\"", "name = \"tiny\"",
       "species.toml:18: key 'preparation.from_state': the saved state's grain at " + state},
      {"box.toml", "width = 0.1", "width = 0.05", "key 'preparation.from_state'"},
      {"count.toml", "count = 15\n[box]", "count = 12\n[box]",
       "count.toml:11: key 'species[1].count': is 12 but the saved state"},
      {"missing.toml", "seed = 3", "from_state = \"nowhere.csv\"",
       "missing.toml:18: key 'preparation.from_state': no such file or directory"},
  };
  for (const Bad& b : bad) {
    std::string text = kPile;
    text.replace(text.find(b.from), b.from.size(), b.to);
    if (b.name != "missing.toml")
      text.replace(text.find("seed = 3"), 8, "from_state = \"" + state + "\"");
    std::ofstream(dir_ / b.name) << text;
    const auto o = run({"run", (dir_ / b.name).string(), "--out", (dir_ / "bad").string()});
    EXPECT_EQ(o.code, 2) << b.name << o.output;
    EXPECT_NE(o.output.find(b.want), std::string::npos) << b.name << ": " << o.output;
  }
}

}  // namespace
}  // namespace gs
