// Trigger: when a periodic action runs (steps, taps, wall-clock minutes) and its saved state
#include <gtest/gtest.h>

#include <vector>

#include "core/trigger.hpp"

namespace gs {
namespace {

std::vector<std::int64_t> firing_steps(Trigger t, std::int64_t from, std::int64_t to) {
  std::vector<std::int64_t> out;
  for (std::int64_t s = from; s <= to; ++s)
    if (t.fires({s, -1, -1.0})) out.push_back(s);
  return out;
}

TEST(Trigger, NeverFiresByDefault) {
  Trigger t;
  EXPECT_FALSE(t.active());
  for (std::int64_t s = 0; s < 50; ++s) EXPECT_FALSE(t.fires({s, 0, 1e9}));
  EXPECT_EQ(t.steps_to_next(7), std::int64_t{1} << 40);
}

TEST(Trigger, EveryNSteps) {
  const Trigger t = Trigger::every_steps(4);
  EXPECT_TRUE(t.active());
  EXPECT_EQ(firing_steps(t, 1, 13), (std::vector<std::int64_t>{4, 8, 12}));
  EXPECT_EQ(t.steps_to_next(0), 4);
  EXPECT_EQ(t.steps_to_next(5), 3);
  EXPECT_EQ(t.steps_to_next(8), 4);
  // a period of zero or less is no condition
  EXPECT_FALSE(Trigger::every_steps(0).active());
  EXPECT_FALSE(Trigger::every_steps(-3).at_step(0));
}

TEST(Trigger, EveryNthTapBoundary) {
  Trigger t = Trigger::every_taps(3);
  // steps that are no tap boundary never fire, whatever their number
  EXPECT_FALSE(t.fires({3, -1, -1.0}));
  std::vector<std::int64_t> fired;
  for (std::int64_t tap = 0; tap < 10; ++tap)
    if (t.fires({100 + tap, tap, -1.0})) fired.push_back(tap);
  EXPECT_EQ(fired, (std::vector<std::int64_t>{0, 3, 6, 9}));
  Trigger every = Trigger::every_taps(1);
  EXPECT_TRUE(every.fires({17, 5, -1.0}));
}

TEST(Trigger, WallClockMinutesRestartWhenItFires) {
  Trigger t = Trigger::every_minutes(1.0).or_every_steps(1000);
  t.start(10.0);
  EXPECT_FALSE(t.fires({1, -1, 69.0}));
  EXPECT_FALSE(t.fires({2, -1, -1.0}));  // clock not read
  EXPECT_TRUE(t.fires({3, -1, 70.0}));
  EXPECT_FALSE(t.fires({4, -1, 129.0}));
  // firing on steps restarts the wall-clock interval too
  EXPECT_TRUE(t.fires({1000, -1, 120.0}));
  EXPECT_FALSE(t.fires({1001, -1, 179.0}));
  EXPECT_TRUE(t.fires({1002, -1, 180.0}));
}

// a resumed trigger (state loaded from a checkpoint) fires where the uninterrupted one does
TEST(Trigger, ResumedFiresLikeUninterrupted) {
  auto make = [] { return Trigger::every_steps(5).or_every_taps(2).or_every_minutes(0.5); };
  // a fake run: one tap boundary every 7 steps, 4 s of wall time per step
  auto at = [](std::int64_t s) {
    return TriggerTime{s, s % 7 == 0 ? s / 7 : -1, 4.0 * static_cast<double>(s)};
  };
  Trigger whole = make();
  std::vector<std::int64_t> a, b;
  for (std::int64_t s = 1; s <= 60; ++s)
    if (whole.fires(at(s))) a.push_back(s);
  Trigger first = make();
  for (std::int64_t s = 1; s <= 23; ++s)
    if (first.fires(at(s))) b.push_back(s);
  ByteWriter w;
  first.save(w);
  Trigger second = make();
  ByteReader r{w.out, 0, "test"};
  second.load(r);
  EXPECT_TRUE(r.at_end());
  for (std::int64_t s = 24; s <= 60; ++s)
    if (second.fires(at(s))) b.push_back(s);
  EXPECT_EQ(a, b);
  EXPECT_FALSE(a.empty());
}

TEST(Trigger, TruncatedStateIsAnInputError) {
  Trigger t;
  ByteReader r{std::string_view("abc"), 0, "ckpt"};
  EXPECT_THROW(t.load(r), InputError);
}

}  // namespace
}  // namespace gs
