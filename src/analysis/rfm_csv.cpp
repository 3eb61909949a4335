// CSV writer and reader for the RFM analysis outputs
#include "analysis/rfm_csv.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.hpp"
#include "core/input_file.hpp"

namespace gs::rfm {

namespace {

// shortest text that reads back to the same double
std::string number(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// split one line at commas, trimming spaces
std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream s(line);
  while (std::getline(s, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t\r");
    const auto e = cell.find_last_not_of(" \t\r");
    out.push_back(b == std::string::npos ? std::string() : cell.substr(b, e - b + 1));
  }
  return out;
}

double parse_number(const std::string& s, const std::string& where, const std::string& key) {
  // strtod accepts nan/inf, which from_chars of some libraries does not
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size())
    throw InputError(where, key, "column '" + key + "': not a number: '" + s + "'");
  return v;
}

}  // namespace

std::filesystem::path meta_path(const std::filesystem::path& csv) {
  std::filesystem::path p = csv;
  p.replace_extension(".json");
  return p;
}

CsvWriter::CsvWriter(const std::filesystem::path& path, const std::vector<std::string>& columns,
                     const CsvMeta& meta)
    : path_(path), out_(path, std::ios::binary), columns_(columns.size()) {
  if (!out_)
    throw OutputError(path.string() +
                      ": cannot open the file for writing: " + std::strerror(errno));
  // metadata in the sidecar, in the order given
  if (!meta.empty()) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    for (const auto& [k, v] : meta) {
      // whole numbers (the counts n, total, underflow, …) as JSON integers
      if (std::isfinite(v) && v == std::trunc(v) && std::abs(v) < 9007199254740992.0)
        j[k] = static_cast<std::int64_t>(v);
      else if (std::isfinite(v))
        j[k] = v;
      else
        j[k] = nullptr;
    }
    const std::filesystem::path side = meta_path(path);
    std::ofstream js(side);
    js << j.dump(2) << '\n';
    if (!js) throw OutputError(side.string() + ": cannot write the metadata file");
  }
  std::string head;
  for (std::size_t i = 0; i < columns.size(); ++i) head += (i ? "," : "") + columns[i];
  put(head + '\n');
}

void CsvWriter::put(const std::string& line) {
  errno = 0;
  out_.write(line.data(), static_cast<std::streamsize>(line.size()));
  out_.flush();
  if (!out_) {
    const int e = errno;
    // a partial line would read back as a short or wrong row: keep whole rows only
    std::error_code ec;
    std::filesystem::resize_file(path_, complete_, ec);
    throw OutputError(path_.string() + ": write failed: " +
                      (e ? std::strerror(e) : "unknown error") + " (every complete row is kept)");
  }
  complete_ += line.size();
}

void CsvWriter::row(const std::vector<double>& values) {
  if (values.size() != columns_)
    throw InputError(path_.string(), "",
                     "row has " + std::to_string(values.size()) + " values, header has " +
                         std::to_string(columns_));
  std::string line;
  for (std::size_t i = 0; i < values.size(); ++i) line += (i ? "," : "") + number(values[i]);
  put(line + '\n');
}

const std::vector<double>& CsvTable::col(const std::string& name) const {
  const auto it = column.find(name);
  if (it == column.end()) {
    std::string have;
    for (const auto& n : names) have += (have.empty() ? "" : ", ") + n;
    throw InputError(source + ":header", name,
                     "missing column '" + name + "' (the header has: " + have + ")");
  }
  return it->second;
}

CsvTable read_csv(const std::filesystem::path& path) {
  check_input_file(path.string(), "CSV file");
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), "", "cannot open the file for reading");
  return parse_csv(in, path.string());
}

CsvTable parse_csv(std::istream& in, const std::string& name) {
  const std::filesystem::path path(name);
  CsvTable t;
  t.source = name;
  std::string line;
  int lineno = 0;
  // metadata lines, header, rows
  while (std::getline(in, line)) {
    ++lineno;
    const std::string where = path.string() + ":" + std::to_string(lineno);
    if (line.empty()) continue;
    if (line[0] == '#') {
      const auto eq = line.find('=');
      if (eq == std::string::npos) continue;  // a plain comment
      const auto kb = line.find_first_not_of("# ");
      const std::string key = line.substr(kb, eq - kb);
      t.meta[key] = parse_number(line.substr(eq + 1), where, key);
      continue;
    }
    if (t.names.empty()) {
      t.names = split(line);
      // every column once: a repeated name would mix two columns into one
      for (std::size_t i = 0; i < t.names.size(); ++i) {
        const std::string& n = t.names[i];
        if (n.empty() || t.column.count(n))
          throw InputError(where, n,
                           "column " + std::to_string(i + 1) + ": " +
                               (n.empty() ? "empty column name" : "repeated column name"));
        t.column[n];
      }
      continue;
    }
    const auto cells = split(line);
    if (cells.size() != t.names.size())
      throw InputError(where, "",
                       "expected " + std::to_string(t.names.size()) + " values, got " +
                           std::to_string(cells.size()));
    for (std::size_t i = 0; i < cells.size(); ++i)
      t.column[t.names[i]].push_back(parse_number(cells[i], where, t.names[i]));
  }
  if (t.names.empty()) throw InputError(path.string(), "", "no header line");
  // the sidecar of the newer form
  const std::filesystem::path side = meta_path(path);
  if (std::ifstream js(side); js) {
    const nlohmann::json j = nlohmann::json::parse(js, nullptr, false);
    if (j.is_discarded() || !j.is_object())
      throw InputError(side.string(), "", "not a JSON object of metadata");
    for (const auto& [k, v] : j.items()) {
      if (v.is_number())
        t.meta[k] = v.get<double>();
      else if (v.is_null())
        t.meta[k] = std::numeric_limits<double>::quiet_NaN();
    }
  }
  return t;
}

}  // namespace gs::rfm
