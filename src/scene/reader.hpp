// checked reading of one TOML table: every key is looked up once against a list of known
// keys, typed, range-checked, and every failure becomes an InputError naming file:line and
// the full dotted key. Internal to the scene module (parse.cpp); nothing outside needs toml++.
#pragma once
#include <toml++/toml.h>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "scene/names.hpp"

namespace gs::scene_detail {

/// where messages point: the file name and the override marker
struct Ctx {
  std::string file;  ///< name used in messages (path or name_for_messages)
  /// "file:line" of a node, "file: --set k=v" for nodes from overrides, "file" if unknown
  std::string where(const toml::node* n) const;
};

/// source-path prefix given to nodes parsed from a --set override
inline constexpr std::string_view kOverrideTag = "--set ";

/// an allowed interval for a number; open ends exclude the bound
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;
  static Range any() { return {}; }
  static Range positive() { return {0.0, Range{}.hi, true, false}; }
  static Range non_negative() { return {0.0, Range{}.hi, false, false}; }
  static Range unit_interval_open_closed() { return {0.0, 1.0, true, false}; }
  bool contains(double v) const;
  /// "> 0", ">= 0", "in (0, 1]", "finite"
  std::string describe() const;
};

/// shortest text that reads back to the same double ("0.002", "1e-06", "3.0")
std::string format_double(double v);
/// a TOML basic string literal with escapes
std::string quote(std::string_view s);
/// TOML type name of a node for messages ("string", "integer", "float", ...)
std::string_view type_name(const toml::node& n);
/// a node's value as short text for messages
std::string node_text(const toml::node& n);
/// Levenshtein distance, for "did you mean"
std::size_t edit_distance(std::string_view a, std::string_view b);
/// "; did you mean 'x'?" when some candidate is close, else ""
std::string suggestion(std::string_view word, const std::vector<std::string_view>& candidates);

/// a checked view of one table; the constructor rejects unknown keys
class TableReader {
 public:
  /// prefix is the dotted path of this table ("" for the root, "species[1]", "drive")
  TableReader(const Ctx& ctx, const toml::table& table, std::string prefix,
              std::vector<std::string_view> known);

  const toml::table& table() const { return table_; }
  const Ctx& ctx() const { return ctx_; }
  /// full dotted key of k in this table
  std::string key(std::string_view k) const;
  bool has(std::string_view k) const;
  /// the node for a key, or nullptr; the key must be in the known list
  const toml::node* get(std::string_view k) const;
  /// throw at the key's line (or the table's line when the key is absent)
  [[noreturn]] void fail(std::string_view k, const std::string& what) const;

  double number(std::string_view k, double def, Range r) const;
  double number_required(std::string_view k, Range r, std::string_view what) const;
  std::optional<double> number_optional(std::string_view k, Range r) const;
  std::int64_t integer(std::string_view k, std::int64_t def, std::int64_t lo,
                       std::int64_t hi) const;
  std::optional<std::int64_t> integer_optional(std::string_view k, std::int64_t lo,
                                               std::int64_t hi) const;
  bool boolean(std::string_view k, bool def) const;
  std::optional<std::string> string_optional(std::string_view k, bool non_empty) const;
  std::string string(std::string_view k, std::string def, bool non_empty) const;

  /// an enum given by one of its scene spellings
  template <class E>
  E choice(std::string_view k, E def) const {
    auto s = string_optional(k, false);
    if (!s) return def;
    if (auto v = scene_enum<E>(*s)) return *v;
    std::vector<std::string_view> names;
    for (const auto& n : enum_names(E{})) names.push_back(n.name);
    fail(k, "must be one of " + scene_enum_list<E>() + " (got " + quote(*s) + ")" +
                suggestion(*s, names));
  }

 private:
  double to_number(std::string_view k, const toml::node& n, Range r) const;
  const Ctx& ctx_;
  const toml::table& table_;
  std::string prefix_;
  std::vector<std::string_view> known_;
};

/// a sub-table of `parent` by key; nullptr when absent; throws if the node is not a table
const toml::table* sub_table(const TableReader& parent, std::string_view k);
/// an array of tables ([[k]]) inside `parent`; empty when absent; throws on other types
std::vector<const toml::table*> table_array(const TableReader& parent, std::string_view k);

/// apply "dotted.key=value" overrides to a parsed document (value in TOML syntax, or a bare
/// word taken as a string); nodes created here carry the override text as their source path
void apply_override(const Ctx& ctx, toml::table& root, const std::string& text);

/// the first byte ≥ 0x80 outside TOML strings and comments as {line, column} (1-based), or
/// {0, 0} if none. toml++ 3.3.0 reaches undefined behaviour on such bytes (upstream issue 295),
/// so the parser refuses them before toml++ sees the text.
std::pair<int, int> non_ascii_outside_strings(std::string_view text);

}  // namespace gs::scene_detail
