#include "output/json_text.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace gs {
namespace {

using ojson = nlohmann::ordered_json;

// the fewest %g digits that read back as v: the text json_number made it from (nlohmann-json's
// own shortest form is not always the shortest, 0.0521585 comes out as 0.052158499999999997)
std::string float_text(double v) {
  if (!std::isfinite(v)) return "null";
  char text[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, v);
    if (std::strtod(text, nullptr) == v) break;
  }
  return text;
}

std::string scalar_text(const ojson& v) {
  if (v.is_number_float()) return float_text(v.get<double>());
  return v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// one line: objects and arrays with ", " and ": " between their parts
void one_line(const ojson& v, std::string& out) {
  if (v.is_object()) {
    out += '{';
    bool first = true;
    for (const auto& [k, e] : v.items()) {
      if (!first) out += ", ";
      first = false;
      out += scalar_text(ojson(k));
      out += ": ";
      one_line(e, out);
    }
    out += '}';
  } else if (v.is_array()) {
    out += '[';
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (i) out += ", ";
      one_line(v[i], out);
    }
    out += ']';
  } else {
    out += scalar_text(v);
  }
}

}  // namespace

ojson json_number(double v, int digits) {
  if (!std::isfinite(v)) return nullptr;
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, v);
  const std::string_view t(text);
  if (t.find_first_of(".eE") == std::string_view::npos)
    return static_cast<std::int64_t>(std::strtoll(text, nullptr, 10));
  const double back = std::strtod(text, nullptr);
  // %g writes large whole numbers with an exponent; nlohmann-json writes them out in full
  if (back == std::trunc(back) && std::abs(back) < 9.0e15) return static_cast<std::int64_t>(back);
  return back;
}

std::string json_text(const ojson& top, std::initializer_list<std::string_view> row_keys) {
  std::string out = "{";
  bool first = true;
  for (const auto& [k, v] : top.items()) {
    out += first ? "\n  " : ",\n  ";
    first = false;
    out += scalar_text(ojson(k));
    out += ": ";
    const bool rows = std::find(row_keys.begin(), row_keys.end(), k) != row_keys.end();
    if (rows && v.is_array()) {
      out += '[';
      for (std::size_t i = 0; i < v.size(); ++i) {
        out += i ? ",\n    " : "\n    ";
        one_line(v[i], out);
      }
      out += "\n  ]";
    } else {
      one_line(v, out);
    }
  }
  out += first ? "}\n" : "\n}\n";
  return out;
}

nlohmann::json parse_json_lenient(const std::string& text) {
  nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (!j.is_discarded()) return j;
  // outside strings, a word that is no JSON literal (nan, -nan, inf, -inf) becomes null
  std::string fixed;
  fixed.reserve(text.size());
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      fixed += c;
      if (c == '\\' && i + 1 < text.size())
        fixed += text[++i];
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"') in_string = true;
    const bool sign =
        c == '-' && i + 1 < text.size() && std::isalpha(static_cast<unsigned char>(text[i + 1]));
    if (!sign && !std::isalpha(static_cast<unsigned char>(c))) {
      fixed += c;
      continue;
    }
    std::size_t e = i + (sign ? 1 : 0);
    while (e < text.size() && std::isalpha(static_cast<unsigned char>(text[e]))) ++e;
    std::string word = text.substr(i + (sign ? 1 : 0), e - i - (sign ? 1 : 0));
    std::transform(word.begin(), word.end(), word.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    fixed += word == "nan" || word == "inf" || word == "infinity" ? std::string("null")
                                                                  : text.substr(i, e - i);
    i = e - 1;
  }
  return nlohmann::json::parse(fixed, nullptr, false);
}

}  // namespace gs
