// the run loop takes the steps between two looks at the state in one batch (Simulation::run:
// each step's correction predicts the next step). With output.series_every = 1 it looks after
// every step and takes none: the two runs write the same taps, samples and final state, bit for
// bit — a Gear 6 tapping pile (batches up to each tap) and a randomly forced disk gas (velocity
// Verlet's fused kick, batches through the transient; with its trajectory every 250 steps)
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;
using testing::gransim;
using testing::sh;
using testing::slurp;

// runs `scene` with `sets` into dir/<tag>: the exit code
int run(const fs::path& dir, const std::string& tag, const std::string& scene,
        const std::string& sets) {
  return sh(gransim("run " + std::string(GS_SOURCE_DIR) + "/scenes/" + scene + " --out " +
                    (dir / tag).string() + " --quiet " + sets))
      .code;
}

struct TempDir {
  fs::path p = fs::temp_directory_path() / ("gs_batches_" + std::to_string(::getpid()));
  TempDir() { fs::remove_all(p); }
  ~TempDir() { fs::remove_all(p); }
};

TEST(RunBatches, TappingPileWritesTheSameTapsAndState) {
  TempDir d;
  const std::string sets =
      "--set species[0].count=20 --set species[1].count=20 --set preparation.settle_time=0.05 "
      "--set drive.period=0.1 --set drive.taps=3 --set drive.early_rest=false "
      "--set integrator.kind=gear6 --set output.discard_taps=0";
  ASSERT_EQ(run(d.p, "batched", "tap_small_negative_g.toml", sets), 0);
  ASSERT_EQ(run(d.p, "each", "tap_small_negative_g.toml", sets + " --set output.series_every=1"),
            0);
  for (const char* f : {"taps.csv", "segregation.csv", "state.csv"}) {
    const std::string a = slurp(d.p / "batched" / f);
    EXPECT_GT(a.size(), 100u) << f;
    EXPECT_TRUE(a == slurp(d.p / "each" / f)) << f;
  }
  const std::string taps = slurp(d.p / "batched" / "taps.csv");
  EXPECT_EQ(std::count(taps.begin(), taps.end(), '\n'), 5);  // header, tap 0 and three taps
}

TEST(RunBatches, ForcedGasWritesTheSameSamplesAndState) {
  TempDir d;
  const std::string sets =
      "--set species[0].count=300 --set scene.duration=0.006 --set rfm.discard_time=0.003 "
      "--set rfm.sample_every=500 --set render.trajectory_every=250";
  ASSERT_EQ(run(d.p, "batched", "rfm2d_reference.toml", sets), 0);
  ASSERT_EQ(run(d.p, "each", "rfm2d_reference.toml", sets + " --set output.series_every=1"), 0);
  for (const char* f :
       {"state.csv", "rfm.json", "hist_freepath.csv", "moments.csv", "trajectory.xyz"}) {
    const std::string a = slurp(d.p / "batched" / f);
    EXPECT_GT(a.size(), 50u) << f;
    EXPECT_TRUE(a == slurp(d.p / "each" / f)) << f;
  }
}

}  // namespace
}  // namespace gs
