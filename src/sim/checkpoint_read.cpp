// checkpoint reading: the decoder depends on nothing but the core, so the fuzzer
// (fuzz/fuzz_checkpoint.cpp) builds it alone
#include <sys/stat.h>

#include <cstring>
#include <fstream>
#include <iterator>

#include "core/bytes.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "sim/checkpoint.hpp"

namespace gs {
namespace {

// bytes per particle: sp, 4 constants, 9 state arrays, 2 wrap counts (and from version 2
// the label)
constexpr std::size_t kParticleBytes = 4 + 4 * 8 + 9 * 8 + 2 * 4;

}  // namespace

std::uint64_t fnv1a64(std::string_view bytes) {
  std::uint64_t h = 1469598103934665603ULL;
  for (char c : bytes) h = (h ^ static_cast<std::uint8_t>(c)) * 1099511628211ULL;
  return h;
}

Checkpoint decode_checkpoint(std::string_view bytes, const std::string& name) {
  ByteReader r{bytes, 0, name};
  // header: magic, version, endianness, size, checksum
  if (bytes.size() < kCheckpointHeader)
    r.fail(bytes.size(), "not a gransim checkpoint: " + std::to_string(bytes.size()) +
                             " bytes, shorter than the 32-byte header");
  if (std::memcmp(bytes.data(), kCheckpointMagic, 8) != 0)
    r.fail(0, "not a gransim checkpoint (bad magic)");
  r.pos = 8;
  const std::uint32_t version = r.u32("version");
  if (version != kCheckpointVersion && version != 1)
    r.fail(8, "checkpoint version " + std::to_string(version) +
                  " is not supported (this build reads " + std::to_string(kCheckpointVersion) +
                  ")");
  const std::uint32_t endian = r.u32("endianness marker");
  if (endian != kCheckpointEndian)
    r.fail(12, endian == 0x04030201u ? "checkpoint written big-endian; only little-endian is read"
                                     : "bad endianness marker");
  const std::uint64_t size = r.u64("payload size");
  if (size != bytes.size() - kCheckpointHeader)
    r.fail(16, "payload size " + std::to_string(size) + " does not match the file (" +
                   std::to_string(bytes.size() - kCheckpointHeader) + " bytes after the header)");
  const std::uint64_t sum = r.u64("checksum");
  if (sum != fnv1a64(bytes.substr(kCheckpointHeader)))
    r.fail(24, "checksum mismatch: the checkpoint is corrupted");

  // payload
  Checkpoint c;
  c.path = name;
  c.scene_toml = r.str("scene text");
  c.clock_origin = r.f64("clock origin");
  State& s = c.s;
  s.t = r.f64("time");
  s.step = r.i64("step");
  const std::size_t n = r.count(kParticleBytes + (version >= 2 ? 4 : 0), "particle");
  r.i32s(c.sp, n, "species indices");
  for (auto* v : {&c.radius, &c.mass, &c.inv_mass, &c.inv_inertia, &s.x, &s.y, &s.th, &s.vx, &s.vy,
                  &s.omega, &s.ax, &s.ay, &s.alpha})
    r.f64s(*v, n, "particle arrays");
  r.i32s(s.wrap_x, n, "wrap counts");
  r.i32s(s.wrap_y, n, "wrap counts");
  if (version >= 2) {  // the labels: a permutation of 0…N−1
    const std::size_t at_ids = r.pos;
    r.i32s(c.id, n, "particle labels");
    std::vector<char> seen(n, 0);
    for (std::int32_t v : c.id) {
      if (v < 0 || static_cast<std::size_t>(v) >= n || seen[static_cast<std::size_t>(v)])
        r.fail(at_ids, "particle labels are not a permutation of 0…N−1");
      seen[static_cast<std::size_t>(v)] = 1;
    }
  } else {
    c.id.resize(n);
    for (std::size_t k = 0; k < n; ++k) c.id[k] = static_cast<std::int32_t>(k);
  }
  c.integrator = r.u8("integrator kind");
  r.f64s(c.integ, r.count(8, "integrator history"), "integrator history");
  c.degenerate = r.u64("degenerate count");
  const std::size_t at_keys = r.pos;
  c.keys.resize(r.count(8, "contact key"));
  for (PairKey& k : c.keys) k = r.u64("contact key");
  for (std::size_t k = 1; k < c.keys.size(); ++k)
    if (c.keys[k] <= c.keys[k - 1]) r.fail(at_keys, "contact keys are not strictly ascending");
  const std::size_t at_state = r.pos;
  c.contact_state.resize(r.count(24, "contact state"));
  if (!c.contact_state.empty() && c.contact_state.size() != c.keys.size())
    r.fail(at_state, "contact states do not match the contact keys");
  for (ContactState& cs : c.contact_state) {
    cs.spring.spring = r.f64("contact state");
    cs.spring.v_prev = r.f64("contact state");
    cs.h_prev = r.f64("contact state");
  }
  const std::size_t ne = r.count(16, "extras");
  for (std::size_t k = 0; k < ne; ++k) {
    std::string key = r.str("extras key");
    c.extras.entries[key] = r.str("extras value");
  }
  if (r.pos != bytes.size()) r.fail(r.pos, "trailing bytes after the last field");
  return c;
}

Checkpoint read_checkpoint(const std::string& path) {
  check_input_file(path, "checkpoint file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open checkpoint");
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(path, "", "cannot read checkpoint");
  return decode_checkpoint(bytes, path);
}

}  // namespace gs
