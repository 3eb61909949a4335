// little-endian byte streams for checkpoints: the writer appends to a string, the reader checks
// every length against what is left and names the source and byte offset of any problem
#pragma once
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"

namespace gs {

struct ByteWriter {
  std::string out;
  void u8(std::uint8_t v) { out.push_back(static_cast<char>(v)); }
  void u32(std::uint32_t v) {
    for (int k = 0; k < 4; ++k) u8(static_cast<std::uint8_t>(v >> (8 * k)));
  }
  void u64(std::uint64_t v) {
    for (int k = 0; k < 8; ++k) u8(static_cast<std::uint8_t>(v >> (8 * k)));
  }
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void i64(std::int64_t v) { u64(static_cast<std::uint64_t>(v)); }
  void f64(double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, 8);
    u64(b);
  }
  void str(std::string_view s) {
    u64(s.size());
    out.append(s.data(), s.size());
  }
  /// values only (the reader is told the count)
  void f64s(const std::vector<double>& v) {
    for (double x : v) f64(x);
  }
  void i32s(const std::vector<int>& v) {
    for (int x : v) i32(x);
  }
  /// count, then values
  void vec(const std::vector<double>& v) {
    u64(v.size());
    f64s(v);
  }
  void vec(const std::vector<long>& v) {
    u64(v.size());
    for (long x : v) i64(x);
  }
};

struct ByteReader {
  std::string_view in;
  std::size_t pos = 0;
  std::string name;  ///< the source, for messages

  [[noreturn]] void fail(std::size_t at, const std::string& what) const {
    throw InputError(name + ": byte offset " + std::to_string(at), "", what);
  }
  void need(std::size_t n, const char* what) const {
    if (in.size() - pos < n)
      fail(pos, std::string("truncated checkpoint: ") + what + " needs " + std::to_string(n) +
                    " bytes, " + std::to_string(in.size() - pos) + " left");
  }
  bool at_end() const { return pos == in.size(); }
  std::uint8_t u8(const char* what) {
    need(1, what);
    return static_cast<std::uint8_t>(in[pos++]);
  }
  std::uint32_t u32(const char* what) {
    need(4, what);
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k)
      v |= std::uint32_t(static_cast<std::uint8_t>(in[pos + k])) << (8 * k);
    pos += 4;
    return v;
  }
  std::uint64_t u64(const char* what) {
    need(8, what);
    std::uint64_t v = 0;
    for (int k = 0; k < 8; ++k)
      v |= std::uint64_t(static_cast<std::uint8_t>(in[pos + k])) << (8 * k);
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
      fail(at, std::string("truncated checkpoint: implausible ") + what + " count " +
                   std::to_string(n) + " (only " + std::to_string(in.size() - pos) +
                   " bytes left)");
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
  /// count then values, as ByteWriter::vec wrote them
  void vec(std::vector<double>& v, const char* what) { f64s(v, count(8, what), what); }
  void vec(std::vector<long>& v, const char* what) {
    v.resize(count(8, what));
    for (long& x : v) x = i64(what);
  }
  /// like vec, but the length must be `n` (an accumulator whose layout the scene fixes)
  void vec_sized(std::vector<double>& v, std::size_t n, const char* what) {
    const std::size_t at = pos;
    const std::size_t m = count(8, what);
    if (m != n)
      fail(at, std::string(what) + ": " + std::to_string(m) + " values stored, the scene needs " +
                   std::to_string(n));
    f64s(v, n, what);
  }
};

}  // namespace gs
