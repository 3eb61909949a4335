// JSON files in gransim's layout, built and written with nlohmann-json: one top-level key per
// line, tables of rows one row per line (a manifest or a summary reads as a table and a
// text search finds a whole row), numbers with as many digits as the measurement carries
#pragma once
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace gs {

/// `v` as printf's %.*g with `digits` significant digits writes it: an integer when that text
/// is one, else the double the text reads back as (json_text writes it with the same digits;
/// only whole values of 10^digits and more lose printf's exponent form); null when not finite
nlohmann::ordered_json json_number(double v, int digits);

/// the object `top` as text: each key on a line of its own, indented by two spaces; the arrays
/// named in `row_keys` one element per line, indented by four ("[\n  ]" when empty); any other
/// value on one line, objects as {"k": v, "k2": [a, b]}. Strings as nlohmann-json writes them
/// (invalid UTF-8 replaced by U+FFFD), other numbers in %g form with the fewest digits that read
/// back exactly, non-finite ones as null. Ends with a newline.
std::string json_text(const nlohmann::ordered_json& top,
                      std::initializer_list<std::string_view> row_keys = {});

/// JSON text parsed, bare nan, inf and -inf numbers (files of older versions) read as null;
/// a discarded value when the text is not JSON
nlohmann::json parse_json_lenient(const std::string& text);

}  // namespace gs
