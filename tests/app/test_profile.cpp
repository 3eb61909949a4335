// `gransim run --profile`: the wall time of each stage of the step as a table at the end, and
// in run.json ("profile") beside the step loop's wall time ("step_loop_s")
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;
using testing::gransim;
using testing::sh;
using testing::slurp;

TEST(RunProfile, TableAtTheEndAndEveryStageInRunJson) {
  const fs::path dir = fs::temp_directory_path() / ("gs_profile_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const auto r = sh(gransim("run " + std::string(GS_SOURCE_DIR) +
                            "/scenes/paper_pile.toml --set scene.duration=0.01 --quiet --profile "
                            "--out " +
                            dir.string()));
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(slurp(dir / "run.json"));
  ASSERT_TRUE(j.contains("profile"));
  double sum = 0.0;
  for (const char* stage : {"drive", "predict", "broad_phase", "pairs", "accelerate", "kick",
                            "correct", "predict_next", "place_next", "health"}) {
    ASSERT_TRUE(j["profile"].contains(stage)) << stage;
    EXPECT_GE(j["profile"][stage].get<double>(), 0.0) << stage;
    sum += j["profile"][stage].get<double>();
    EXPECT_NE(r.output.find(stage), std::string::npos) << "no row for " << stage << " in\n"
                                                       << r.output;
  }
  const double loop = j["step_loop_s"].get<double>();
  EXPECT_GT(loop, 0.0);
  // how the stages add up to the steps' time is tested on an injected clock
  // (tests/sim/test_step_profile.cpp): wall times themselves depend on the machine's load
  const auto timed = j["profile_timed_steps"].get<std::int64_t>();
  EXPECT_GT(timed, 0);
  EXPECT_LE(timed, j["steps"].get<std::int64_t>());
  EXPECT_GT(sum, 0.0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace gs
