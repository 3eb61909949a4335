// checks of numeric command-line options whose messages give the bound as a user writes it
// ("must be >= 0 (got -1)"), never the 309 digits of the largest double
#pragma once
#include <CLI/CLI.hpp>
#include <cmath>
#include <string>

namespace gs::cli_check {

/// a finite number >= 0 (`strict`: > 0)
inline CLI::Validator at_least_zero(bool strict) {
  return CLI::Validator(
      [strict](std::string& text) -> std::string {
        double v = 0.0;
        try {
          std::size_t used = 0;
          v = std::stod(text, &used);
          if (used != text.size()) return "expected a number, got '" + text + "'";
        } catch (const std::exception&) {
          return "expected a number, got '" + text + "'";
        }
        if (!std::isfinite(v) || (strict ? !(v > 0.0) : !(v >= 0.0)))
          return std::string("must be a finite number ") + (strict ? "> 0" : ">= 0") + " (got " +
                 text + ")";
        return {};
      },
      strict ? "POSITIVE" : "NONNEGATIVE");
}

inline const CLI::Validator non_negative = at_least_zero(false);
inline const CLI::Validator positive = at_least_zero(true);

}  // namespace gs::cli_check
