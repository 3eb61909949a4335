// the tapping drivers as pure schedules (P.37, P.38): hand values of g(t) at the phase
// boundaries, the settling phase before the protocol clock, the measurement trigger, and the
// protocol clock's early rest (docs/physics.md §2.4)
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "drive/protocol.hpp"
#include "drive/schedule.hpp"
#include "world/prepare.hpp"

namespace gs {
namespace {

constexpr double kG = 9.81;

DriveSpec negative_g(double g_p, double t1, double T) {
  DriveSpec d;
  d.kind = DriveKind::NegativeG;
  d.g_p = g_p;
  d.t1 = t1;
  d.period = T;
  return d;
}

DriveSpec rotating_g(double f, double relax) {
  DriveSpec d;
  d.kind = DriveKind::RotatingG;
  d.f = f;
  d.relax = relax;
  return d;
}

void expect_g(Vec2 g, double gx, double gy) {
  EXPECT_NEAR(g.x, gx, 1e-12 * kG);
  EXPECT_NEAR(g.y, gy, 1e-12 * kG);
}

// (P.37): g = 9.81·e_y·g_p inside the pulse t̃ < t1, −9.81·e_y after it, period T
TEST(NegativeG, HandValuesAtThePhaseBoundaries) {
  const DriveSpec d = negative_g(6.0, 0.1, 3.0);
  const double eps = 1e-9;
  expect_g(gravity_at(d, 0.0, 0.0), 0.0, 6.0 * kG);  // the pulse starts at t̃ = 0
  expect_g(gravity_at(d, 0.0, 0.05), 0.0, 58.86);
  expect_g(gravity_at(d, 0.0, 0.1 - eps), 0.0, 58.86);
  expect_g(gravity_at(d, 0.0, 0.1 + eps), 0.0, -kG);  // relaxation
  expect_g(gravity_at(d, 0.0, 2.9), 0.0, -kG);
  expect_g(gravity_at(d, 0.0, 3.0 - eps), 0.0, -kG);
  expect_g(gravity_at(d, 0.0, 3.0 + eps), 0.0, 58.86);  // the next period
  expect_g(gravity_at(d, 0.0, 3.1 + eps), 0.0, -kG);
  expect_g(gravity_at(d, 0.0, 3000.05), 0.0, 58.86);  // tap 1000
  const DrivePhase p = drive_phase(d, 0.0, 7.25);
  EXPECT_EQ(p.tap, 2);
  EXPECT_NEAR(p.t_in, 1.25, 1e-12);
  EXPECT_FALSE(p.exciting);
  EXPECT_FALSE(p.settling);
  EXPECT_DOUBLE_EQ(drive_period(d), 3.0);
  EXPECT_DOUBLE_EQ(excitation_length(d), 0.1);
}

// (P.38) with the window t̃ < 2π/ω (docs/physics.md §8.3): f = 0.5 Hz turns gravity once in 2 s,
// then 3 s of relaxation, T = 2π/ω + 3 s = 5 s
TEST(RotatingG, HandValuesOverOneTurn) {
  const DriveSpec d = rotating_g(0.5, 3.0);
  EXPECT_DOUBLE_EQ(drive_period(d), 5.0);
  EXPECT_DOUBLE_EQ(excitation_length(d), 2.0);
  expect_g(gravity_at(d, 0.0, 0.0), 0.0, -kG);  // ωt̃ = 0: down
  expect_g(gravity_at(d, 0.0, 0.5), kG, 0.0);   // ωt̃ = π/2: (sin, −cos) = (1, 0)
  expect_g(gravity_at(d, 0.0, 1.0), 0.0, kG);   // π: up (the printed window ω/2π = 0.5 s
                                                // would already have stopped the turn)
  expect_g(gravity_at(d, 0.0, 1.5), -kG, 0.0);  // 3π/2
  const Vec2 g = gravity_at(d, 0.0, 0.25);      // π/4
  EXPECT_NEAR(g.x, kG * std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(g.y, -kG * std::sqrt(0.5), 1e-12);
  expect_g(gravity_at(d, 0.0, 2.0 + 1e-9), 0.0, -kG);  // relaxation
  expect_g(gravity_at(d, 0.0, 4.99), 0.0, -kG);
  expect_g(gravity_at(d, 0.0, 5.5), kG, 0.0);  // the next turn, tap 1
  // |g| is 9.81 all along the turn
  for (double t = 0.0; t < 2.0; t += 0.0137)
    EXPECT_NEAR(std::hypot(gravity_at(d, 0.0, t).x, gravity_at(d, 0.0, t).y), kG, 1e-12);
}

// before the clock origin the pile settles under plain gravity; the protocol runs on t − origin
TEST(Schedule, SettlingBeforeTheProtocolClock) {
  const DriveSpec d = negative_g(6.0, 0.1, 3.0);
  const double origin = 2.0;
  EXPECT_TRUE(drive_phase(d, origin, 1.999).settling);
  expect_g(gravity_at(d, origin, 0.05), 0.0, -kG);  // would be a pulse without the settling time
  expect_g(gravity_at(d, origin, 1.999), 0.0, -kG);
  expect_g(gravity_at(d, origin, 2.05), 0.0, 58.86);
  expect_g(gravity_at(d, origin, 2.15), 0.0, -kG);
  EXPECT_EQ(drive_phase(d, origin, 5.05).tap, 1);
  const DriveSpec r = rotating_g(1.0, 3.0);
  expect_g(gravity_at(r, 1.0, 0.25), 0.0, -kG);  // settling, not a quarter turn
  expect_g(gravity_at(r, 1.0, 1.25), kG, 0.0);
  // constant gravity ignores the clock; its direction is (gx, gy) normalised
  DriveSpec c;
  c.kind = DriveKind::Gravity;
  c.gx = 3.0;
  c.gy = -4.0;
  expect_g(gravity_at(c, 10.0, 1.0), 0.6 * kG, -0.8 * kG);
}

// the clock origin half a step past the settling time: every pulse lasts exactly t1/Δt force
// evaluations (t_n = n·Δt), and the measurement trigger fires once per period, at the step
// before the pulse
TEST(ProtocolClock, PulsesLastExactlyT1OverDtAndTriggersFireOncePerTap) {
  for (double dt : {1e-3, 5e-5}) {
    SceneSpec s;
    s.drive = negative_g(6.0, 0.1, 0.5);
    s.prep.settle_time = 0.3;
    s.integrator.dt = dt;
    World w;
    ProtocolClock(s).start(w);
    const auto steps = static_cast<long>(std::llround((0.3 + 3 * 0.5) / dt));
    int pulse_evals = 0, triggers = 0;
    double first_trigger = -1.0;
    for (long n = 0; n <= steps; ++n) {
      const double t = static_cast<double>(n) * dt;
      if (gravity_at(s.drive, w.clock_origin, t).y > 0) ++pulse_evals;
      if (excitation_starts_next(s.drive, w.clock_origin, t, dt)) {
        if (triggers++ == 0) first_trigger = t;
      }
    }
    // 3 full periods after settling: 3 pulses and 4 triggers (the first at the end of settling,
    // the last at t = 1.8 s, just before the 4th pulse)
    EXPECT_EQ(pulse_evals, 3 * static_cast<int>(std::llround(0.1 / dt))) << "dt = " << dt;
    EXPECT_EQ(triggers, 4) << "dt = " << dt;
    EXPECT_NEAR(first_trigger, 0.3, 1e-9) << "dt = " << dt;
  }
}

// a one-grain World whose velocity the test sets by hand
World one_grain(const SceneSpec& s) {
  World w = make_world(s);
  w.add_particle(0, {0.05, 0.05}, 0.0);
  return w;
}

SceneSpec early_rest_scene(bool on) {
  SceneSpec s;
  MaterialSpec m;
  m.name = "m";
  s.materials.push_back(m);
  SpeciesSpec sp;
  sp.name = "g";
  sp.radius = 0.009;
  sp.count = 1;
  s.species.push_back(sp);
  s.box.width = 0.1;
  s.drive = negative_g(6.0, 0.1, 3.0);
  s.drive.early_rest = on;
  s.drive.rest_speed = 1e-3;
  s.drive.rest_energy = 1e-6;
  s.drive.rest_hold = 0.1;
  s.drive.taps = 2;
  s.integrator.dt = 1e-3;
  return s;
}

// early rest: a pile at rest from t = 1 s for the hold time 0.1 s ends tap 0's relaxation at
// t = 1.1 s; the protocol time jumps to the end of the period (t stays continuous), the next
// step starts the next pulse, 1.9 s of simulated time are saved
TEST(ProtocolClock, EarlyRestEndsARelaxationAfterTheHoldTime) {
  const SceneSpec s = early_rest_scene(true);
  World w = one_grain(s);
  ProtocolClock clock(s);
  clock.start(w);
  const double dt = s.integrator.dt;
  double ended_at = -1.0;
  for (long n = 1; n <= 1500 && ended_at < 0; ++n) {
    w.s.t = static_cast<double>(n) * dt;
    w.s.vx[0] = w.s.t < 1.0 - 1e-9 ? 0.5 : 2e-4;  // moving, then below 1 mm/s
    if (clock.after_step(w) == ClockEvent::RestEnded) ended_at = w.s.t;
  }
  ASSERT_GT(ended_at, 0.0);
  EXPECT_NEAR(ended_at, 1.1, 1.5 * dt);
  EXPECT_EQ(clock.early_ends(), 1);
  EXPECT_NEAR(clock.time_saved(), 3.0 - ended_at, 1e-9);
  const DrivePhase now = drive_phase(s.drive, w.clock_origin, w.s.t);
  EXPECT_EQ(now.tap, 0);
  EXPECT_NEAR(now.t_in, 3.0 - dt / 2, 1e-9);
  EXPECT_TRUE(excitation_starts_next(s.drive, w.clock_origin, w.s.t, dt));
  EXPECT_GT(gravity_at(s.drive, w.clock_origin, w.s.t + dt).y, 0.0);  // the next pulse
  EXPECT_FALSE(clock.done(w));
  EXPECT_NEAR(clock.progress(w), 3.0, 1e-9);  // counts the skipped rest as done
}

// rest inside a pulse does not count, a single fast grain resets the hold, and with
// early_rest = false nothing ever moves the clock
TEST(ProtocolClock, EarlyRestNeedsTheWholeHoldInsideARelaxation) {
  for (bool on : {true, false}) {
    const SceneSpec s = early_rest_scene(on);
    World w = one_grain(s);
    ProtocolClock clock(s);
    clock.start(w);
    const double dt = s.integrator.dt, origin = w.clock_origin;
    int ends = 0;
    for (long n = 1; n <= 1000; ++n) {
      w.s.t = static_cast<double>(n) * dt;
      // at rest all along, except one fast step every 0.08 s (shorter than the hold)
      w.s.vx[0] = n % 80 == 0 ? 0.01 : 0.0;
      ends += clock.after_step(w) == ClockEvent::RestEnded;
    }
    EXPECT_EQ(ends, 0);
    EXPECT_EQ(w.clock_origin, origin);
  }
}

// the quench on one grain in a harmonic well x'' = −ω²(x − x0) (ω = 4π: a KE peak every
// 0.125 s), stepped by hand; on ClockEvent::Quench the test zeroes the velocity as the run does.
// Script: fast (0.3 m/s, the flight) until t = 1 s, then released at rest 2 mm from x0
// (largest speed 25 mm/s); optionally a kick of 0.1 m/s at t = 2 s
struct Well {
  double x0 = 0.05, omega = 4.0 * M_PI;
  std::vector<double> events;  ///< times of the Quench events
  double x_after_first = 0.0;  ///< |x − x0| just after the first reset, m
};

SceneSpec quench_scene(bool on) {
  SceneSpec s = early_rest_scene(false);
  s.drive.quench = on;
  s.drive.quench_speed = 0.05;
  s.drive.quench_hold = 0.05;
  return s;
}

// steps n in [from, to) of the script with clock c on world w
void well_steps(ProtocolClock& c, World& w, Well& well, long from, long to, bool kick, double dt) {
  for (long n = from; n < to; ++n) {
    w.s.t = static_cast<double>(n) * dt;
    if (w.s.t < 1.0 - 1e-9) {
      w.s.vx[0] = 0.3;
      w.s.x[0] = well.x0 + 2e-3;
    } else {
      if (std::abs(w.s.t - 1.0) < dt / 2) w.s.vx[0] = 0.0;  // released at rest
      if (kick && std::abs(w.s.t - 2.0) < dt / 2) w.s.vx[0] += 0.1;
      // symplectic Euler in the well
      w.s.vx[0] -= well.omega * well.omega * (w.s.x[0] - well.x0) * dt;
      w.s.x[0] += w.s.vx[0] * dt;
    }
    if (c.after_step(w) == ClockEvent::Quench) {
      w.s.vx[0] = 0.0;
      if (well.events.empty()) well.x_after_first = std::abs(w.s.x[0] - well.x0);
      well.events.push_back(w.s.t);
    }
  }
}

TEST(ProtocolClock, QuenchArmsAfterTheHoldAndResetsAtTheKineticEnergyPeak) {
  for (bool on : {true, false}) {
    const SceneSpec s = quench_scene(on);
    World w = one_grain(s);
    ProtocolClock clock(s);
    clock.start(w);
    Well well;
    well_steps(clock, w, well, 1, 2900, false, s.integrator.dt);
    if (!on) {
      EXPECT_TRUE(well.events.empty());
      continue;
    }
    // released at t = 1 s at rest: armed from 1.05 s, the first peak at x0 a quarter period
    // (0.125 s) after the release; the reset leaves the grain at rest within a step of x0
    ASSERT_FALSE(well.events.empty());
    EXPECT_NEAR(well.events.front(), 1.125, 2.5 * s.integrator.dt);
    EXPECT_LT(well.x_after_first, 0.05 * 2e-3);
    EXPECT_EQ(clock.quench_events(), static_cast<std::int64_t>(well.events.size()));
    for (double t : well.events) EXPECT_GT(t, 1.05);
    EXPECT_EQ(clock.early_ends(), 0);  // early_rest off: the quench alone never ends a period
  }
}

TEST(ProtocolClock, QuenchIsDisarmedByAFastGrainAndIdleInAnExcitation) {
  const SceneSpec s = quench_scene(true);
  World w = one_grain(s);
  ProtocolClock clock(s);
  clock.start(w);
  Well well;
  // a kick at t = 2 s to 0.1 m/s: faster than quench_speed for most of each cycle, never slow
  // for the hold at a peak: no reset after it, the grain keeps swinging
  well_steps(clock, w, well, 1, 2990, true, s.integrator.dt);
  ASSERT_FALSE(well.events.empty());
  for (double t : well.events) EXPECT_LT(t, 2.0);
  EXPECT_GT(std::abs(w.s.vx[0]) + well.omega * std::abs(w.s.x[0] - well.x0), 0.09);
  // into the next pulse and its flight: nothing while exciting, the state is reset
  const std::size_t before = well.events.size();
  for (long n = 2990; n < 3100; ++n) {
    w.s.t = static_cast<double>(n) * s.integrator.dt;
    w.s.vx[0] = n % 2 ? 1e-3 : 2e-3;  // slow and with peaks, but inside the pulse first
    if (clock.after_step(w) == ClockEvent::Quench) well.events.push_back(w.s.t);
  }
  EXPECT_EQ(well.events.size(), before);
}

// checkpoint: a clock saved while armed and mid-rise and loaded into a fresh one continues with
// the same events; a clock state written before the quench existed loads with it idle
TEST(ProtocolClock, QuenchStateSurvivesSaveAndLoad) {
  const SceneSpec s = quench_scene(true);
  const double dt = s.integrator.dt;
  World w1 = one_grain(s);
  ProtocolClock c1(s);
  c1.start(w1);
  Well a;
  well_steps(c1, w1, a, 1, 1100, false, dt);  // armed at 1.05 s, rising to the 1.125 s peak
  ByteWriter out;
  c1.save(out);
  World w2 = w1;
  ProtocolClock c2(s);
  ByteReader in{out.out, 0, "test"};
  c2.load(in);
  EXPECT_TRUE(in.at_end());
  Well b = a;
  well_steps(c1, w1, a, 1100, 2900, false, dt);
  well_steps(c2, w2, b, 1100, 2900, false, dt);
  EXPECT_EQ(a.events, b.events);
  EXPECT_EQ(c1.quench_events(), c2.quench_events());
  EXPECT_EQ(w1.s.x[0], w2.s.x[0]);
  // the four early-rest fields alone (an older checkpoint)
  ByteWriter old;
  old.f64(-1.0);
  old.i64(-1);
  old.i64(3);
  old.f64(1.5);
  ProtocolClock c3(s);
  ByteReader in3{old.out, 0, "old"};
  c3.load(in3);
  EXPECT_EQ(c3.early_ends(), 3);
  EXPECT_EQ(c3.quench_events(), 0);
}

// the run ends after the step that measures the last tap
TEST(ProtocolClock, DoneAfterTheLastTapIsMeasured) {
  const SceneSpec s = early_rest_scene(false);  // 2 taps of 3 s, no settling
  World w = one_grain(s);
  ProtocolClock clock(s);
  clock.start(w);
  EXPECT_DOUBLE_EQ(clock.nominal_duration(), 6.0);
  w.s.t = 5.999;
  EXPECT_FALSE(clock.done(w));
  w.s.t = 6.0;
  EXPECT_TRUE(clock.done(w));
  EXPECT_TRUE(excitation_starts_next(s.drive, w.clock_origin, w.s.t, s.integrator.dt));
}

}  // namespace
}  // namespace gs

namespace gs {
namespace {
// drives without gravity never get any, not even during the first half step
TEST(GravitySchedule, NoGravityForNoneAndRandomForce) {
  for (DriveKind k : {DriveKind::None, DriveKind::RandomForce}) {
    DriveSpec d;
    d.kind = k;
    for (double t : {0.0, 0.25, 0.5, 1.0}) {
      EXPECT_EQ(gravity_at(d, 0.5, t).x, 0.0);
      EXPECT_EQ(gravity_at(d, 0.5, t).y, 0.0);
    }
  }
}
}  // namespace
}  // namespace gs
