// the arguments of the module's functions and methods, checked before any of them reaches the
// library, as the command line checks its options: a bad one raises InputError naming the
// function and the argument ("tap_analysis: argument 'discard': must be >= 0 (got -5)")
#pragma once
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <sstream>
#include <string>

#include "core/error.hpp"

namespace gs::py_bind {

/// an InputError about one argument: where() is the function, key() the argument, and the
/// message "FUNCTION: argument 'NAME': what"
class ArgumentError : public InputError {
 public:
  ArgumentError(const std::string& function, const std::string& name, const std::string& what)
      : InputError(function, name, what),
        message_(function + ": argument '" + name + "': " + what) {}
  const char* what() const noexcept override { return message_.c_str(); }

 private:
  std::string message_;
};

class Args {
 public:
  explicit Args(const char* function) : fn_(function) {}

  /// a finite number
  const Args& finite(const char* name, double v) const {
    if (!std::isfinite(v)) fail(name, "must be a finite number", v);
    return *this;
  }
  /// a finite number > 0
  const Args& positive(const char* name, double v) const {
    if (!(std::isfinite(v) && v > 0.0)) fail(name, "must be a finite number > 0", v);
    return *this;
  }
  /// a finite number >= 0
  const Args& non_negative(const char* name, double v) const {
    if (!(std::isfinite(v) && v >= 0.0)) fail(name, "must be a finite number >= 0", v);
    return *this;
  }
  /// a number strictly between lo and hi (a probability, a confidence level)
  const Args& open(const char* name, double v, double lo, double hi) const {
    if (!(v > lo && v < hi))
      fail(name, "must lie strictly between " + text(lo) + " and " + text(hi), v);
    return *this;
  }
  /// a whole number in [lo, hi]
  const Args& count(const char* name, long long v, long long lo, long long hi) const {
    if (v < lo || v > hi) {
      std::string what = "must be a whole number ";
      what += hi == std::numeric_limits<long long>::max()
                  ? ">= " + std::to_string(lo)
                  : "from " + std::to_string(lo) + " to " + std::to_string(hi);
      throw ArgumentError(fn_, name, what + " (got " + std::to_string(v) + ")");
    }
    return *this;
  }
  /// every value finite
  const Args& all_finite(const char* name, std::span<const double> v) const {
    for (std::size_t k = 0; k < v.size(); ++k)
      if (!std::isfinite(v[k]))
        throw ArgumentError(
            fn_, name,
            "must hold finite numbers only (item " + std::to_string(k) + " is " + text(v[k]) + ")");
    return *this;
  }
  /// at least n values
  const Args& length_at_least(const char* name, std::size_t size, std::size_t n) const {
    if (size < n)
      throw ArgumentError(
          fn_, name,
          "needs at least " + std::to_string(n) + " values (got " + std::to_string(size) + ")");
    return *this;
  }
  /// a requirement between arguments
  const Args& require(bool ok, const char* name, const std::string& what) const {
    if (!ok) throw ArgumentError(fn_, name, what);
    return *this;
  }
  [[noreturn]] void fail(const char* name, const std::string& what) const {
    throw ArgumentError(fn_, name, what);
  }

  /// a number as a short text (%g: never hundreds of digits)
  static std::string text(double v) {
    std::ostringstream s;
    s.precision(6);
    s << v;
    return s.str();
  }

 private:
  [[noreturn]] void fail(const char* name, const std::string& what, double v) const {
    throw ArgumentError(fn_, name, what + " (got " + text(v) + ")");
  }
  const char* fn_;
};

}  // namespace gs::py_bind
