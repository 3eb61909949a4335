// each Simulation splits its particles among the threads by its own team's measured speeds:
// two simulations in one process (the Python module, a study, these tests) never move each
// other's split, and however uneven a split is, the results are the same bits
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "scene/parse.hpp"
#include "sim/state_file.hpp"
#include "test_world.hpp"

namespace gs {
namespace {

using testing::state_hash;
using testing::Threads;

// the paper's settled pile of 1184 decagons: its polygon pairs run on the team, whose force
// pass measures it
Simulation pile_sim() {
  const std::string src = GS_SOURCE_DIR;
  const SceneSpec s = parse_scene_file(src + "/scenes/paper_pile.toml");
  World w = make_world(s);
  read_state_file(w, src + "/scenes/data/paper_pile_settled.csv");
  return Simulation(std::move(w), SimSettings::from(s));
}

// thread 0 of the team's split of n particles ends here
std::size_t split(const Simulation& sim, std::size_t n) {
  return sim.team().particles(n, 0, 2).end;
}

// a split far from equal: thread 1 measured ten times slower, many times over
void skew(ThreadTeam& team) {
  for (int k = 0; k < 40; ++k) {
    const double items[2] = {500, 500}, secs[2] = {1e-5, 1e-4};
    team.speeds().update(items, secs, 2);
  }
}

TEST(ThreadTeam, TwoSimulationsKeepTheirOwnSplits) {
  const Threads two(2);
  Simulation a = pile_sim(), b = pile_sim();
  const std::size_t n = 100000;
  skew(b.team());
  const std::size_t b_split = split(b, n);
  ASSERT_GT(b_split, n * 3 / 4) << "the skewed split gives thread 0 most particles";
  a.run(20);
#ifdef _OPENMP
  EXPECT_TRUE(a.team().speeds().has(2)) << "a's force pass measured its team";
  // a's timings moved a's split only (towards a's own threads' speeds, not b's skew)
  EXPECT_LT(split(a, n), b_split);
#endif
  EXPECT_EQ(split(b, n), b_split) << "a's steps moved b's split";
  // and b's own steps move b's split alone
  const std::size_t a_split = split(a, n);
  b.run(5);
  EXPECT_EQ(split(a, n), a_split) << "b's steps moved a's split";
}

// the particle split decides only where work runs: a strongly uneven one gives the bits of one
// thread
TEST(ThreadTeam, AnUnevenSplitGivesTheSameBits) {
  std::uint64_t one_thread = 0;
  {
    const Threads single(1);
    Simulation sim = pile_sim();
    sim.run(15);
    one_thread = state_hash(sim.world());
  }
  const Threads two(2);
  Simulation sim = pile_sim();
  for (int k = 0; k < 15; ++k) {
    skew(sim.team());  // before each step: the force pass's own timings move it back
    sim.step();
  }
  EXPECT_EQ(state_hash(sim.world()), one_thread);
}

}  // namespace
}  // namespace gs
