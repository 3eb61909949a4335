// checked TOML reading (see reader.hpp): locations, value formatting, typed getters,
// unknown-key suggestions and --set overrides
#include "scene/reader.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace gs::scene_detail {

// ---------------------------------------------------------------------------------------
// locations and text

std::string Ctx::where(const toml::node* n) const {
  if (n) {
    const auto& src = n->source();
    // nodes from an override carry the override text as their source path
    if (src.path && src.path->rfind(kOverrideTag, 0) == 0) return file + ": " + *src.path;
    if (src.begin.line > 0) return file + ":" + std::to_string(src.begin.line);
  }
  return file;
}

namespace {
// shortest round-trip text of a double, as to_chars writes it ("1e-06", "3", "nan")
std::string shortest(double v) {
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}
}  // namespace

std::string format_double(double v) {
  std::string s = shortest(v);
  // keep floats looking like floats in TOML ("3" would read back as an integer)
  if (s.find_first_of(".eni") == std::string::npos) s += ".0";
  return s;
}

std::string quote(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string_view type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "table";
    case toml::node_type::array:
      return "array";
    case toml::node_type::string:
      return "string";
    case toml::node_type::integer:
      return "integer";
    case toml::node_type::floating_point:
      return "float";
    case toml::node_type::boolean:
      return "boolean";
    case toml::node_type::date:
      return "date";
    case toml::node_type::time:
      return "time";
    case toml::node_type::date_time:
      return "date-time";
    default:
      return "nothing";
  }
}

std::string node_text(const toml::node& n) {
  if (auto s = n.as_string()) return quote(s->get());
  if (auto i = n.as_integer()) return std::to_string(i->get());
  if (auto f = n.as_floating_point()) return shortest(f->get());
  if (auto b = n.as_boolean()) return b->get() ? "true" : "false";
  return std::string("a ") + std::string(type_name(n));
}

// ---------------------------------------------------------------------------------------
// "did you mean"

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // classic two-row Levenshtein
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t sub = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

namespace {
// lower case without '_' and '-': "G_p", "gp" and "g-p" all read "gp"
std::string squash(std::string_view s) {
  std::string out;
  for (char c : s)
    if (c != '_' && c != '-') out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}
}  // namespace

std::string suggestion(std::string_view word, const std::vector<std::string_view>& candidates) {
  // the closest candidate, if within a third of the word's length (at least 2 edits);
  // a candidate equal up to case and separators wins outright
  std::string_view best;
  std::size_t best_d = std::numeric_limits<std::size_t>::max();
  for (auto c : candidates) {
    std::size_t d = squash(word) == squash(c) ? 0 : edit_distance(word, c);
    if (d < best_d) best_d = d, best = c;
  }
  std::size_t limit = std::max<std::size_t>(2, word.size() / 3);
  if (best.empty() || best_d > limit) return "";
  return "; did you mean '" + std::string(best) + "'?";
}

// ---------------------------------------------------------------------------------------
// ranges

bool Range::contains(double v) const {
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (hi_open ? !(v < hi) : !(v <= hi)) return false;
  return true;
}

std::string Range::describe() const {
  bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (!has_lo && !has_hi) return "a finite number";
  if (!has_hi) return (lo_open ? "> " : ">= ") + shortest(lo);
  if (!has_lo) return (hi_open ? "< " : "<= ") + shortest(hi);
  return std::string("in ") + (lo_open ? "(" : "[") + shortest(lo) + ", " + shortest(hi) +
         (hi_open ? ")" : "]");
}

// ---------------------------------------------------------------------------------------
// the table reader

TableReader::TableReader(const Ctx& ctx, const toml::table& table, std::string prefix,
                         std::vector<std::string_view> known)
    : ctx_(ctx), table_(table), prefix_(std::move(prefix)), known_(std::move(known)) {
  // every key present must be one we know
  for (const auto& [k, node] : table_) {
    std::string_view name = k.str();
    if (std::find(known_.begin(), known_.end(), name) != known_.end()) continue;
    std::string accepted;
    for (auto kk : known_) accepted += (accepted.empty() ? "" : ", ") + std::string(kk);
    throw InputError(
        ctx_.where(&node), key(name),
        "unknown key" + suggestion(name, known_) + " (accepted here: " + accepted + ")");
  }
}

std::string TableReader::key(std::string_view k) const {
  return prefix_.empty() ? std::string(k) : prefix_ + "." + std::string(k);
}

bool TableReader::has(std::string_view k) const { return get(k) != nullptr; }

const toml::node* TableReader::get(std::string_view k) const {
  // a key missing from the known list is a bug in the parser, not in the scene
  if (std::find(known_.begin(), known_.end(), k) == known_.end())
    throw std::logic_error("scene parser reads undeclared key " + key(k));
  return table_.get(k);
}

void TableReader::fail(std::string_view k, const std::string& what) const {
  const toml::node* n = get(k);
  // a missing key in the root table has no line to point at
  std::string where = (n || !prefix_.empty()) ? ctx_.where(n ? n : &table_) : ctx_.file;
  throw InputError(where, key(k), what);
}

double TableReader::to_number(std::string_view k, const toml::node& n, Range r) const {
  // integers are accepted where floats are expected
  double v = 0;
  if (auto f = n.as_floating_point())
    v = f->get();
  else if (auto i = n.as_integer())
    v = static_cast<double>(i->get());
  else
    fail(k, "expected a number (float or integer), got " + std::string(type_name(n)) + " " +
                node_text(n));
  if (!std::isfinite(v)) fail(k, "must be a finite number (got " + shortest(v) + ")");
  if (!r.contains(v)) fail(k, "must be " + r.describe() + " (got " + shortest(v) + ")");
  return v;
}

double TableReader::number(std::string_view k, double def, Range r) const {
  const toml::node* n = get(k);
  return n ? to_number(k, *n, r) : def;
}

double TableReader::number_required(std::string_view k, Range r, std::string_view what) const {
  const toml::node* n = get(k);
  if (!n) fail(k, "missing: required (" + std::string(what) + ", " + r.describe() + ")");
  return to_number(k, *n, r);
}

std::optional<double> TableReader::number_optional(std::string_view k, Range r) const {
  const toml::node* n = get(k);
  if (!n) return std::nullopt;
  return to_number(k, *n, r);
}

std::optional<std::int64_t> TableReader::integer_optional(std::string_view k, std::int64_t lo,
                                                          std::int64_t hi) const {
  const toml::node* n = get(k);
  if (!n) return std::nullopt;
  auto i = n->as_integer();
  if (!i) fail(k, "expected an integer, got " + std::string(type_name(*n)) + " " + node_text(*n));
  std::int64_t v = i->get();
  if (v < lo || v > hi) {
    // an int-sized upper bound is only worth naming when it was exceeded
    bool huge = hi >= std::numeric_limits<int>::max() && v <= hi;
    std::string range = huge ? ">= " + std::to_string(lo)
                             : "in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    fail(k, "must be an integer " + range + " (got " + std::to_string(v) + ")");
  }
  return v;
}

std::int64_t TableReader::integer(std::string_view k, std::int64_t def, std::int64_t lo,
                                  std::int64_t hi) const {
  return integer_optional(k, lo, hi).value_or(def);
}

bool TableReader::boolean(std::string_view k, bool def) const {
  const toml::node* n = get(k);
  if (!n) return def;
  auto b = n->as_boolean();
  if (!b)
    fail(k, "expected a boolean (true or false), got " + std::string(type_name(*n)) + " " +
                node_text(*n));
  return b->get();
}

std::optional<std::string> TableReader::string_optional(std::string_view k, bool non_empty) const {
  const toml::node* n = get(k);
  if (!n) return std::nullopt;
  auto s = n->as_string();
  if (!s)
    fail(k,
         "expected a string (in quotes), got " + std::string(type_name(*n)) + " " + node_text(*n));
  if (non_empty && s->get().empty()) fail(k, "must not be empty");
  return s->get();
}

std::string TableReader::string(std::string_view k, std::string def, bool non_empty) const {
  return string_optional(k, non_empty).value_or(std::move(def));
}

const toml::table* sub_table(const TableReader& parent, std::string_view k) {
  const toml::node* n = parent.get(k);
  if (!n) return nullptr;
  if (auto t = n->as_table()) return t;
  std::string hint = n->is_array() ? " (write [" + parent.key(k) + "], not [[...]])" : "";
  parent.fail(k,
              "expected a table [" + parent.key(k) + "], got " + std::string(type_name(*n)) + hint);
}

std::vector<const toml::table*> table_array(const TableReader& parent, std::string_view k) {
  std::vector<const toml::table*> out;
  const toml::node* n = parent.get(k);
  if (!n) return out;
  auto arr = n->as_array();
  if (!arr)
    parent.fail(k, "expected an array of tables [[" + parent.key(k) + "]], got " +
                       std::string(type_name(*n)) + " (write [[" + parent.key(k) +
                       "]] before each entry)");
  // every element must itself be a table
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const toml::node& e = (*arr)[i];
    auto t = e.as_table();
    if (!t) {
      // the element has no key of its own: report it with its index
      throw InputError(parent.ctx().where(&e), parent.key(k) + "[" + std::to_string(i) + "]",
                       "expected a table, got " + std::string(type_name(e)));
    }
    out.push_back(t);
  }
  return out;
}

// ---------------------------------------------------------------------------------------
// overrides

namespace {
struct Segment {
  std::string name;
  std::optional<std::size_t> index;
};

bool is_key_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
}

std::string trim(std::string_view s) {
  auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return "";
  auto e = s.find_last_not_of(" \t");
  return std::string(s.substr(b, e - b + 1));
}

// "species[1].radius" → {species,1} {radius}; nullopt if malformed
std::optional<std::vector<Segment>> split_key(std::string_view key) {
  std::vector<Segment> out;
  std::size_t i = 0;
  while (true) {
    Segment seg;
    while (i < key.size() && is_key_char(key[i])) seg.name += key[i++];
    if (seg.name.empty()) return std::nullopt;
    if (i < key.size() && key[i] == '[') {
      std::size_t j = key.find(']', i);
      if (j == std::string_view::npos || j == i + 1) return std::nullopt;
      std::size_t idx = 0;
      auto digits = key.substr(i + 1, j - i - 1);
      auto r = std::from_chars(digits.data(), digits.data() + digits.size(), idx);
      if (r.ec != std::errc() || r.ptr != digits.data() + digits.size()) return std::nullopt;
      seg.index = idx;
      i = j + 1;
    }
    out.push_back(std::move(seg));
    if (i == key.size()) return out;
    if (key[i] != '.') return std::nullopt;
    ++i;
  }
}
}  // namespace

std::pair<int, int> non_ascii_outside_strings(std::string_view t) {
  int line = 1, col = 0;
  std::size_t i = 0;
  auto starts = [&](std::string_view w) { return t.substr(i, w.size()) == w; };
  auto advance = [&](std::size_t k) {
    for (std::size_t e = std::min(t.size(), i + k); i < e; ++i) {
      if (t[i] == '\n') {
        ++line;
        col = 0;
      } else {
        ++col;
      }
    }
  };
  // a quote opens a string only where TOML can start one: at the start of a line (a quoted
  // key), after '=', '[', ',', '{' or '.' (blanks between). Anywhere else toml++ scans over it
  // as part of a bare value, and a non-ASCII byte behind it would reach the unreachable branch
  // of its whitespace test (fuzz: `x = Z'''` then U+02BF), so such a quote is an ordinary byte.
  // a backslash followed by a non-ASCII byte in a basic string: toml++ tests that byte for
  // whitespace (a line-ending backslash) and reaches the same branch (fuzz: `"""\` U+0465);
  // it is no valid escape anyway
  auto escapes_non_ascii = [&] {
    return t[i] == '\\' && i + 1 < t.size() && static_cast<unsigned char>(t[i + 1]) >= 0x80;
  };
  char prev = '\n';       // the last non-blank byte outside strings ('\n' at a line start)
  bool in_value = false;  // past the '=' of this line: a '.' is a decimal point, not a key dot
  int eqs = 0;            // '=' outside strings on this line
  bool plain_key = true;  // everything before the first '=' is a bare (dotted) key
  while (i < t.size()) {
    const unsigned char c = static_cast<unsigned char>(t[i]);
    if (c >= 0x80) return {line, col + 1};
    const char before = prev;
    const bool string_start = std::string_view("\n=[,{").find(prev) != std::string_view::npos ||
                              (prev == '.' && !in_value);  // (fuzz: `x = 0."` then U+FE7B)
    if (c != ' ' && c != '\t' && c != '\r') prev = static_cast<char>(c);
    if (eqs == 0 && c != '=' && !std::isalnum(c) && c != '_' && c != '-' && c != '.' && c != ' ' &&
        c != '\t')
      plain_key = false;
    if (c == '=') {
      in_value = true;
      ++eqs;
    }
    if (c == '\n') {
      in_value = false;
      eqs = 0;
      plain_key = true;
    }
    if (c == '#') {  // comment: to the end of the line
      while (i < t.size() && t[i] != '\n') advance(1);
    } else if (!string_start && (c == '"' || c == '\'')) {
      advance(1);  // not a string here: what follows is checked like any other byte
    } else if (starts("\"\"\"") || starts("'''")) {  // multi-line strings
      const std::string_view close = t.substr(i, 3);
      advance(3);
      while (i < t.size() && !starts(close)) {
        // ASCII only: toml++ tests bytes after line-ending backslashes and newlines here
        if (static_cast<unsigned char>(t[i]) >= 0x80) return {line, col + 1};
        advance(t[i] == '\\' && close[0] == '"' ? 2 : 1);
      }
      advance(3);
    } else if (c == '"' || c == '\'') {  // one-line strings (basic strings have escapes)
      const char q = static_cast<char>(c);
      // non-ASCII text only in a plain `key = "…"` value, which toml++ reads as a string
      // and nothing else; in keys, arrays and inline tables it is refused (fuzzing found
      // three ways to the unreachable branch around strings)
      // (the first '=' of a line after a bare key: fuzz `h =-"\"="` then U+03A5)
      const bool text_ok = before == '=' && eqs == 1 && plain_key;
      advance(1);
      while (i < t.size() && t[i] != q && t[i] != '\n') {
        if (!text_ok && static_cast<unsigned char>(t[i]) >= 0x80) return {line, col + 1};
        if (q == '"' && escapes_non_ascii()) return {line, col + 2};
        advance(t[i] == '\\' && q == '"' ? 2 : 1);
      }
      advance(1);
    } else {
      advance(1);
    }
  }
  return {0, 0};
}

void apply_override(const Ctx& ctx, toml::table& root, const std::string& text) {
  std::string where = ctx.file + ": " + std::string(kOverrideTag) + text;
  auto eq = text.find('=');
  std::string key = trim(std::string_view(text).substr(0, eq));
  auto segs = eq == std::string::npos ? std::nullopt : split_key(key);
  if (!segs)
    throw InputError(where, "",
                     "expected dotted.key=value, e.g. drive.g_p=8 or species[0].count=100");
  std::string value = trim(std::string_view(text).substr(eq + 1));

  // the value in TOML syntax; a bare word that is not TOML is taken as a string
  std::string source = std::string(kOverrideTag) + text;
  toml::table parsed;
  try {
    // non-ASCII outside quotes is never valid TOML here: take it as a bare-word string
    if (non_ascii_outside_strings("v = " + value).first != 0)
      throw toml::parse_error("non-ASCII character", toml::source_region{});
    parsed = toml::parse("v = " + value, source);
  } catch (const toml::parse_error& e) {
    if (!value.empty() && std::string_view("[{\"'").find(value[0]) != std::string_view::npos)
      throw InputError(where, key,
                       "cannot parse the value as TOML: " + std::string(e.description()));
    parsed = toml::parse("v = " + quote(value), source);
  }

  // walk to the parent table, creating plain tables on the way
  toml::table* cur = &root;
  std::string path;
  for (std::size_t s = 0; s + 1 < segs->size(); ++s) {
    const Segment& seg = (*segs)[s];
    path += (path.empty() ? "" : ".") + seg.name;
    toml::node* n = cur->get(seg.name);
    if (seg.index) {
      auto arr = n ? n->as_array() : nullptr;
      if (!arr) throw InputError(where, key, "'" + path + "' is not an array of tables");
      if (*seg.index >= arr->size())
        throw InputError(where, key,
                         "'" + path + "' has " + std::to_string(arr->size()) + " entries (index " +
                             std::to_string(*seg.index) + " is out of range)");
      cur = (*arr)[*seg.index].as_table();
      if (!cur) throw InputError(where, key, "'" + path + "[...]' is not a table");
      path += '[';
      path += std::to_string(*seg.index);
      path += ']';
      continue;
    }
    if (!n) n = cur->insert_or_assign(seg.name, toml::table{}).first->second.as_table();
    if (n->is_array())
      throw InputError(where, key,
                       "'" + path + "' is an array of tables; write " + path + "[0]." +
                           (*segs)[s + 1].name + " etc.");
    cur = n->as_table();
    if (!cur) throw InputError(where, key, "'" + path + "' is not a table");
  }
  const Segment& last = segs->back();
  if (last.index)
    throw InputError(where, key, "cannot set one array element; give the whole array");

  // move the parsed node in, keeping its source (the override text) for messages
  toml::node* v = parsed.get("v");
  v->visit([&](auto& node) { cur->insert_or_assign(last.name, std::move(node)); });
}

}  // namespace gs::scene_detail
