// snapshots: the contact CSV is ContactSet::records row for row, as `render --chains` draws
// them; a run killed and resumed ends with the uninterrupted run's snapshots byte for byte
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "binary.hpp"
#include "output/particles/snapshot_files.hpp"
#include "scene/parse.hpp"
#include "sim/simulation.hpp"
#include "view/render_world.hpp"
#include "world/prepare.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;
using testing::Launch;
using testing::Outcome;
using testing::run_binary;
using testing::slurp;

// the CSV as rows of numbers, after checking the header
std::vector<std::vector<double>> read_contacts(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  std::string head;
  for (const auto& c : contact_columns()) head += (head.empty() ? "" : ",") + c;
  EXPECT_EQ(line, head);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> r;
    std::istringstream ls(line);
    for (std::string cell; std::getline(ls, cell, ',');) r.push_back(std::stod(cell));
    EXPECT_EQ(r.size(), contact_columns().size()) << line;
    rows.push_back(r);
  }
  return rows;
}

TEST(Snapshots, ContactRowsAreTheForceChainsRecords) {
  SceneSpec s = parse_scene_string(testing::tiny_tapping_scene(1), "tiny.toml");
  World w = make_world(s);
  place_particles(w, s);
  Simulation sim(std::move(w), SimSettings::from(s));
  sim.run(4000);  // settling: a pile with wall and grain contacts, some sliding
  const World& cw = sim.world();
  const ContactSet& c = sim.contacts();
  std::ostringstream out;
  write_contacts_csv(out, cw, c);
  const auto rows = read_contacts(out.str());
  const auto chains = force_chain_lines(cw, c);
  ASSERT_EQ(rows.size(), c.records.size());
  ASSERT_EQ(rows.size(), chains.size());
  ASSERT_GT(rows.size(), 30u);
  const std::size_t n = cw.size();
  int walls = 0, sliding = 0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto& r = rows[k];
    const ContactRecord& rec = c.records[k];
    const std::size_t i = key_i(rec.key), j = key_j(rec.key);
    // labels, wall index, point, normal and forces of the record, bit for bit (%.17g)
    EXPECT_EQ(r[0], cw.id[i]);
    EXPECT_EQ(r[3], rec.s.x);
    EXPECT_EQ(r[4], rec.s.y);
    EXPECT_EQ(r[5], rec.n.x);
    EXPECT_EQ(r[6], rec.n.y);
    EXPECT_EQ(r[7], rec.fn);
    EXPECT_EQ(r[8], rec.ft);
    EXPECT_EQ(r[11], rec.overlap);
    if (j >= n) {
      ++walls;
      EXPECT_EQ(r[1], -1);
      EXPECT_EQ(r[2], static_cast<double>(j - n));
      // a wall's chain segment ends at the contact point
      EXPECT_EQ(r[3], chains[k].b.x);
      EXPECT_EQ(r[4], chains[k].b.y);
    } else {
      EXPECT_EQ(r[1], cw.id[j]);
      EXPECT_EQ(r[2], -1);
    }
    // the chain's width is |F_n| of the same contact
    EXPECT_EQ(std::abs(r[7]), chains[k].force);
    // (fx, fy) = F_n n + F_t perp(n), the force on j (or the wall)
    EXPECT_NEAR(r[9], r[7] * r[5] - r[8] * r[6], 1e-12 * (std::abs(r[7]) + std::abs(r[8])));
    EXPECT_NEAR(r[10], r[7] * r[6] + r[8] * r[5], 1e-12 * (std::abs(r[7]) + std::abs(r[8])));
    // sliding: on the Coulomb cap μ F_n (μ = 0.6 here)
    if (r[12] == 1.0) {
      ++sliding;
      EXPECT_NEAR(std::abs(r[8]), 0.6 * r[7], 1e-9 * r[7]);
    } else {
      EXPECT_LT(std::abs(r[8]), 0.6 * r[7]);
    }
  }
  EXPECT_GT(walls, 0);
  EXPECT_GT(sliding, 0);
}

// every file under DIR/snapshots
std::map<std::string, std::string> snapshot_files(const fs::path& dir) {
  std::map<std::string, std::string> m;
  for (const auto& e : fs::directory_iterator(dir / "snapshots"))
    m[e.path().filename().string()] = slurp(e.path());
  return m;
}

std::size_t checkpoints(const fs::path& dir) {
  std::size_t k = 0;
  if (fs::exists(dir))
    for (const auto& e : fs::directory_iterator(dir))
      k += e.path().filename().string().rfind("checkpoint-", 0) == 0;
  return k;
}

TEST(Snapshots, KilledRunResumesToTheUninterruptedSnapshots) {
  const fs::path tmp = testing::fresh_test_dir("gs_snapshots");
  std::ofstream(tmp / "tiny.toml") << testing::tiny_tapping_scene(10);
  auto args = [&](const fs::path& out) {
    return std::vector<std::string>{"run",
                                    (tmp / "tiny.toml").string(),
                                    "--out",
                                    out.string(),
                                    "--quiet",
                                    "--set",
                                    "output.snapshots.at_taps=true",
                                    "--set",
                                    "output.snapshots.every_time=0.35",
                                    "--set",
                                    "output.checkpoint_steps=2000"};
  };
  Launch env;
  env.env = {"OMP_NUM_THREADS=1"};
  env.alarm_s = 120;
  const auto t0 = std::chrono::steady_clock::now();
  const Outcome ref = run_binary(args(tmp / "ref"), tmp / "ref.log", env);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(ref.exited && ref.code == 0) << ref.output;
  const auto want = snapshot_files(tmp / "ref");
  EXPECT_EQ(want.count("snapshots.pvd"), 1u);
  EXPECT_EQ(want.count("snap_000000.vtp"), 1u);
  // a kill half way (moved until the killed run has a checkpoint and has not finished)
  Launch kill = env;
  kill.signal = SIGKILL;
  kill.signal_after_s = 0.5 * wall;
  const fs::path dir = tmp / "killed";
  Outcome killed;
  double too_early = 0.0, too_late = -1.0;
  for (int attempt = 0; attempt < 10; ++attempt) {
    fs::remove_all(dir);
    killed = run_binary(args(dir), tmp / "killed.log", kill);
    if (killed.exited) {
      too_late = kill.signal_after_s;
    } else if (checkpoints(dir) == 0) {
      too_early = kill.signal_after_s;
    } else {
      break;
    }
    kill.signal_after_s =
        too_late > 0.0 ? 0.5 * (too_early + too_late) : kill.signal_after_s + 0.1 * wall;
  }
  ASSERT_FALSE(killed.exited) << "the run ended before the kill";
  ASSERT_GT(checkpoints(dir), 0u);
  const Outcome r = run_binary({"resume", dir.string(), "--quiet"}, tmp / "resume.log", env);
  ASSERT_TRUE(r.exited && r.code == 0) << r.output;
  const auto got = snapshot_files(dir);
  ASSERT_EQ(got.size(), want.size());
  for (const auto& [name, bytes] : want) {
    ASSERT_TRUE(got.count(name)) << name << " missing after resume";
    EXPECT_TRUE(got.at(name) == bytes) << name << " differs after a kill and resume";
  }
  fs::remove_all(tmp);
}

}  // namespace
}  // namespace gs
