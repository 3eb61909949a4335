// derived quantities checked before a run starts: a step count that would overflow or never
// finish is refused with exit 2 naming the key, instead of a "completed" run of zero steps
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;
using testing::run_binary;

TEST(InputBounds, StepCountsThatCannotBeRunAreRefused) {
  const fs::path tmp = fs::temp_directory_path() / ("gs-bounds-" + std::to_string(::getpid()));
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  const std::string demo = std::string(GS_SOURCE_DIR) + "/scenes/demo.toml";
  const std::string tap = std::string(GS_SOURCE_DIR) + "/scenes/tap_small_negative_g.toml";
  struct Case {
    std::string scene, set;
  };
  for (const Case& c :
       {Case{demo, "integrator.dt=1e-300"}, Case{demo, "scene.duration=1e300"},
        Case{tap, "preparation.settle_time=1e30"}, Case{tap, "drive.taps=2000000000"}}) {
    const fs::path out = tmp / "run";
    const auto r =
        run_binary({"run", c.scene, "--out", out.string(), "--set", c.set, "-q"}, tmp / "log.txt");
    EXPECT_TRUE(r.exited) << c.set;
    EXPECT_EQ(r.code, 2) << c.set << "\n" << r.output;
    EXPECT_NE(r.output.find("integrator.dt"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("completed"), std::string::npos) << r.output;
    // refused before the directory was touched
    EXPECT_FALSE(fs::exists(out / "run.json")) << c.set;
  }
  fs::remove_all(tmp);
}

}  // namespace
}  // namespace gs
