// checkpoints: a run stopped after N steps, written, read back and continued for M steps ends
// bitwise where the uninterrupted N + M run ends, for every integrator and drive that matters
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>

#include "core/error.hpp"
#include "sim/builders.hpp"
#include "sim/checkpoint.hpp"
#include "sim/simulation.hpp"
#include "world/prepare.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;

// FNV-1a over every state array, the time and the step
std::uint64_t state_hash(const World& w) {
  std::uint64_t h = 1469598103934665603ULL;
  auto mix = [&](const void* d, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(d);
    for (std::size_t k = 0; k < n; ++k) h = (h ^ p[k]) * 1099511628211ULL;
  };
  for (const auto* v :
       {&w.s.x, &w.s.y, &w.s.th, &w.s.vx, &w.s.vy, &w.s.omega, &w.s.ax, &w.s.ay, &w.s.alpha})
    mix(v->data(), v->size() * sizeof(double));
  mix(w.s.wrap_x.data(), w.s.wrap_x.size() * sizeof(int));
  mix(&w.s.t, sizeof w.s.t);
  mix(&w.s.step, sizeof w.s.step);
  return h;
}

std::unique_ptr<Simulation> start(const SceneSpec& s, double clock_origin = 0.0) {
  World w = make_world(s);
  place_particles(w, s);
  w.clock_origin = clock_origin;
  return std::make_unique<Simulation>(std::move(w), SimSettings::from(s));
}

fs::path temp_file(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("gs_ckpt_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d / name;
}

// run n + m straight; run n, checkpoint to disk, restore, run m: same hash and contacts
void expect_bitwise_continuation(const SceneSpec& s, std::int64_t n, std::int64_t m,
                                 const std::string& tag, bool need_contacts = true,
                                 double clock_origin = 0.0) {
  auto straight = start(s, clock_origin);
  straight->run(n + m);

  auto first = start(s, clock_origin);
  first->run(n);
  CheckpointExtras ex;
  ex.entries["taps.csv.offset"] = "1234";
  ex.entries["binary"] = std::string("\0\xff\x01", 3);
  const fs::path p = temp_file(tag + ".gsck");
  write_checkpoint(*first, s, ex, p.string());
  first.reset();

  const Checkpoint c = read_checkpoint(p.string());
  EXPECT_EQ(c.extras.entries, ex.entries);
  Simulation resumed = restore_simulation(c);
  EXPECT_EQ(resumed.world().s.step, n);
  EXPECT_EQ(resumed.world().clock_origin, clock_origin) << tag;
  resumed.run(m);
  EXPECT_EQ(state_hash(resumed.world()), state_hash(straight->world())) << tag;
  EXPECT_EQ(resumed.contacts().keys, straight->contacts().keys) << tag;
  if (need_contacts) {
    EXPECT_FALSE(straight->contacts().keys.empty()) << tag << ": the test should have contacts";
  }
  fs::remove(p);
}

SceneSpec pile(IntegratorKind k) {
  SceneSpec s = build::decagon_pile(40, 0.10, 0.40, 7);
  s.integrator.kind = k;
  return s;
}

TEST(Checkpoint, DecagonPileContinuesBitwiseGear6) {
  expect_bitwise_continuation(pile(IntegratorKind::Gear6), 3000, 1000, "gear6");
}

TEST(Checkpoint, DecagonPileContinuesBitwiseVelocityVerlet) {
  expect_bitwise_continuation(pile(IntegratorKind::VelocityVerlet), 3000, 1000, "vv");
}

TEST(Checkpoint, DecagonPileContinuesBitwisePositionVerletAndEuler) {
  expect_bitwise_continuation(pile(IntegratorKind::PositionVerlet), 3000, 500, "pv");
  expect_bitwise_continuation(pile(IntegratorKind::SemiImplicitEuler), 3000, 500, "euler");
}

// the random force depends on the seed and the step only; the checkpoint falls between two
// centre-of-mass removals (every 100 steps)
TEST(Checkpoint, DiskGasWithRandomForceContinuesBitwise) {
  SceneSpec s = build::disk_gas(60, 0.3, 0.9, 0.9, 11);
  s.drive.kind = DriveKind::RandomForce;
  s.drive.D = 1e-9;
  expect_bitwise_continuation(s, 1550, 700, "rfm", false);
}

// gravity schedules are functions of t and the protocol clock's origin, run state the
// checkpoint stores
TEST(Checkpoint, RotatingAndNegativeGravityContinueBitwise) {
  SceneSpec s = pile(IntegratorKind::VelocityVerlet);
  s.drive.kind = DriveKind::RotatingG;
  s.drive.f = 10.0;
  s.drive.relax = 0.0;
  expect_bitwise_continuation(s, 2500, 1500, "rotating", true, 0.05);
  s.drive.kind = DriveKind::NegativeG;
  s.drive.t1 = 0.02;
  s.drive.period = 0.1;
  expect_bitwise_continuation(s, 2500, 1500, "negative", true, 0.05);
}

// a checkpoint an earlier build wrote (the fuzz seed of a tapping run) gives its clock origin
// back as run state; the scene it embeds has no such key
TEST(Checkpoint, EarlierCheckpointsGiveTheClockOriginBack) {
  const Checkpoint c =
      read_checkpoint(std::string(GS_SOURCE_DIR) + "/fuzz/corpus/checkpoint/run_tapping.gsck");
  EXPECT_NE(c.clock_origin, 0.0);  // (early rest moved it back past 0)
  EXPECT_EQ(c.scene_toml.find("clock_origin"), std::string::npos);
  const Simulation sim = restore_simulation(c);
  EXPECT_EQ(sim.world().clock_origin, c.clock_origin);
}

// every header field and every byte of the payload is checked
TEST(Checkpoint, DamagedBytesAreInputErrorsNamingFileAndOffset) {
  const SceneSpec s = pile(IntegratorKind::Gear6);
  auto sim = start(s);
  sim->run(200);
  const std::string good = encode_checkpoint(*sim, s, {});
  EXPECT_NO_THROW(decode_checkpoint(good, "good.gsck"));
  auto expect_error = [&](std::string bytes, const std::string& what) {
    try {
      decode_checkpoint(bytes, "bad.gsck");
      ADD_FAILURE() << "accepted: " << what;
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("bad.gsck: byte offset"), std::string::npos) << m;
      EXPECT_NE(m.find(what), std::string::npos) << m;
    }
  };
  expect_error("", "shorter than the 32-byte header");
  expect_error("GSCKPT__" + good.substr(8, 40), "bad magic");
  std::string b = good;
  b[8] = 3;
  expect_error(b, "version 3");
  b = good;
  std::swap(b[12], b[15]);
  std::swap(b[13], b[14]);
  expect_error(b, "big-endian");
  expect_error(good.substr(0, good.size() - 1), "payload size");
  expect_error(good + "x", "payload size");
  b = good;
  b[good.size() / 2] ^= 0x10;
  expect_error(b, "checksum mismatch");
  // a payload that is consistent but short (checksum recomputed): truncation is named
  std::string payload = good.substr(kCheckpointHeader, 100);
  b = good.substr(0, kCheckpointHeader) + payload;
  const std::uint64_t size = payload.size(), sum = fnv1a64(payload);
  for (int k = 0; k < 8; ++k) {
    b[16 + k] = static_cast<char>(size >> (8 * k));
    b[24 + k] = static_cast<char>(sum >> (8 * k));
  }
  expect_error(b, "truncated checkpoint");

  // the labels (version 2): a repeated label is named; a version-1 file (no labels, as
  // written before spatial sorting) reads back with each slot its own label
  const std::size_t n = sim->world().size();
  std::string ids;
  for (std::uint32_t k = 0; k < n; ++k)
    for (int q = 0; q < 4; ++q) ids += static_cast<char>(k >> (8 * q));
  const std::size_t at = good.find(ids, kCheckpointHeader);
  ASSERT_NE(at, std::string::npos);
  auto reseal = [](std::string bytes, std::uint32_t version) {
    const std::string p = bytes.substr(kCheckpointHeader);
    const std::uint64_t sz = p.size(), h = fnv1a64(p);
    for (int k = 0; k < 4; ++k) bytes[8 + k] = static_cast<char>(version >> (8 * k));
    for (int k = 0; k < 8; ++k) {
      bytes[16 + k] = static_cast<char>(sz >> (8 * k));
      bytes[24 + k] = static_cast<char>(h >> (8 * k));
    }
    return bytes;
  };
  b = good;
  b[at + 4] = 0;  // slot 1 labelled 0 as well
  expect_error(reseal(b, 2), "particle labels are not a permutation");
  const std::string v1 = reseal(good.substr(0, at) + good.substr(at + ids.size()), 1);
  const Checkpoint c1 = decode_checkpoint(v1, "v1.gsck");
  ASSERT_EQ(c1.id.size(), n);
  for (std::size_t k = 0; k < n; ++k) EXPECT_EQ(c1.id[k], static_cast<int>(k));
  EXPECT_EQ(c1.s.x, decode_checkpoint(good, "good.gsck").s.x);
}

// missing files and directories are named
TEST(Checkpoint, MissingFileAndDirectoryAreInputErrors) {
  EXPECT_THROW(read_checkpoint("/nonexistent/dir/x.gsck"), InputError);
  EXPECT_THROW(read_checkpoint(fs::temp_directory_path().string()), InputError);
}

}  // namespace
}  // namespace gs

namespace gs {
namespace {

// seeds for the fuzzer and the hostile corpus: GS_WRITE_CHECKPOINT_SEEDS=DIR writes a small
// decagon pile (with contacts) and a disk gas checkpoint into DIR; otherwise nothing happens
TEST(Checkpoint, WritesFuzzSeedsWhenAsked) {
  const char* dir = std::getenv("GS_WRITE_CHECKPOINT_SEEDS");
  if (!dir) GTEST_SKIP() << "set GS_WRITE_CHECKPOINT_SEEDS=DIR to write seed checkpoints";
  const SceneSpec p = build::decagon_pile(8, 0.06, 0.2, 3);
  auto a = start(p);
  a->run(2000);
  CheckpointExtras ex;
  ex.entries["taps.csv.offset"] = "42";
  write_checkpoint(*a, p, ex, std::string(dir) + "/pile.gsck");
  SceneSpec g = build::disk_gas(6, 0.3, 0.9, 0.9, 5);
  g.drive.kind = DriveKind::RandomForce;
  auto b = start(g);
  b->run(100);
  write_checkpoint(*b, g, {}, std::string(dir) + "/gas.gsck");
}

}  // namespace
}  // namespace gs
