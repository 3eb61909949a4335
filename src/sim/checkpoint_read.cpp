// checkpoint reading: the decoder depends on nothing but the core, so the fuzzer
// (fuzz/fuzz_checkpoint.cpp) builds it alone
#include <sys/stat.h>

#include <cstring>
#include <fstream>
#include <iterator>

#include "core/error.hpp"
#include "sim/checkpoint.hpp"

namespace gs {
namespace {

// ---- little-endian reader: every problem names the file and the byte offset ----

struct Reader {
  std::string_view in;
  std::size_t pos = 0;
  const std::string& name;

  [[noreturn]] void fail(std::size_t at, const std::string& what) const {
    throw InputError(name + ": byte offset " + std::to_string(at), "", what);
  }
  void need(std::size_t n, const char* what) const {
    if (in.size() - pos < n)
      fail(pos, std::string("truncated checkpoint: ") + what + " needs " + std::to_string(n) +
                    " bytes, " + std::to_string(in.size() - pos) + " left");
  }
  std::uint8_t u8(const char* what) {
    need(1, what);
    return static_cast<std::uint8_t>(in[pos++]);
  }
  std::uint32_t u32(const char* what) {
    need(4, what);
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v |= std::uint32_t(static_cast<std::uint8_t>(in[pos + k])) << (8 * k);
    pos += 4;
    return v;
  }
  std::uint64_t u64(const char* what) {
    need(8, what);
    std::uint64_t v = 0;
    for (int k = 0; k < 8; ++k) v |= std::uint64_t(static_cast<std::uint8_t>(in[pos + k])) << (8 * k);
    pos += 8;
    return v;
  }
  std::int32_t i32(const char* what) { return static_cast<std::int32_t>(u32(what)); }
  std::int64_t i64(const char* what) { return static_cast<std::int64_t>(u64(what)); }
  double f64(const char* what) {
    const std::uint64_t b = u64(what);
    double v;
    std::memcpy(&v, &b, 8);
    return v;
  }
  /// a count of items of `item` bytes each, checked against the bytes that remain
  std::size_t count(std::size_t item, const char* what) {
    const std::size_t at = pos;
    const std::uint64_t n = u64(what);
    if (item > 0 && n > (in.size() - pos) / item)
      fail(at, std::string("truncated checkpoint: implausible ") + what + " count " + std::to_string(n) + " (only " +
                   std::to_string(in.size() - pos) + " bytes left)");
    return static_cast<std::size_t>(n);
  }
  std::string str(const char* what) {
    const std::size_t n = count(1, what);
    std::string s(in.substr(pos, n));
    pos += n;
    return s;
  }
  void f64s(std::vector<double>& v, std::size_t n, const char* what) {
    need(8 * n, what);
    v.resize(n);
    for (double& x : v) x = f64(what);
  }
  void i32s(std::vector<int>& v, std::size_t n, const char* what) {
    need(4 * n, what);
    v.resize(n);
    for (int& x : v) x = i32(what);
  }
};

// bytes per particle: sp, 4 constants, 9 state arrays, 2 wrap counts
constexpr std::size_t kParticleBytes = 4 + 4 * 8 + 9 * 8 + 2 * 4;

}  // namespace

std::uint64_t fnv1a64(std::string_view bytes) {
  std::uint64_t h = 1469598103934665603ULL;
  for (char c : bytes) h = (h ^ static_cast<std::uint8_t>(c)) * 1099511628211ULL;
  return h;
}

Checkpoint decode_checkpoint(std::string_view bytes, const std::string& name) {
  Reader r{bytes, 0, name};
  // header: magic, version, endianness, size, checksum
  if (bytes.size() < kCheckpointHeader)
    r.fail(bytes.size(), "not a gransim checkpoint: " + std::to_string(bytes.size()) +
                             " bytes, shorter than the 32-byte header");
  if (std::memcmp(bytes.data(), kCheckpointMagic, 8) != 0)
    r.fail(0, "not a gransim checkpoint (bad magic)");
  r.pos = 8;
  const std::uint32_t version = r.u32("version");
  if (version != kCheckpointVersion)
    r.fail(8, "checkpoint version " + std::to_string(version) + " is not supported (this build reads " +
                  std::to_string(kCheckpointVersion) + ")");
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
  const std::size_t n = r.count(kParticleBytes, "particle");
  r.i32s(c.sp, n, "species indices");
  for (auto* v : {&c.radius, &c.mass, &c.inv_mass, &c.inv_inertia, &s.x, &s.y, &s.th, &s.vx,
                  &s.vy, &s.w, &s.ax, &s.ay, &s.aw})
    r.f64s(*v, n, "particle arrays");
  r.i32s(s.wrap_x, n, "wrap counts");
  r.i32s(s.wrap_y, n, "wrap counts");
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
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw InputError(path, "", "checkpoint does not exist");
  if (S_ISDIR(st.st_mode)) throw InputError(path, "", "is a directory, not a checkpoint file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open checkpoint");
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(path, "", "cannot read checkpoint");
  return decode_checkpoint(bytes, path);
}

}  // namespace gs
