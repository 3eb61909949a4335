// CSV writer and reader for the RFM analysis outputs
#include "analysis/rfm_csv.hpp"

#include <charconv>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.hpp"

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
    throw InputError(where, key, "not a number: '" + s + "'");
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
    : path_(path), out_(path), columns_(columns.size()) {
  if (!out_) throw InputError(path.string(), "", "cannot open the file for writing");
  // metadata in the sidecar, in the order given
  if (!meta.empty()) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    for (const auto& [k, v] : meta) {
      if (std::isfinite(v))
        j[k] = v;
      else
        j[k] = nullptr;
    }
    const std::filesystem::path side = meta_path(path);
    std::ofstream js(side);
    js << j.dump(2) << '\n';
    if (!js) throw InputError(side.string(), "", "cannot write the metadata file");
  }
  for (std::size_t i = 0; i < columns.size(); ++i) out_ << (i ? "," : "") << columns[i];
  out_ << '\n';
}

void CsvWriter::row(const std::vector<double>& values) {
  if (values.size() != columns_)
    throw InputError(path_.string(), "", "row has " + std::to_string(values.size()) +
                                             " values, header has " + std::to_string(columns_));
  for (std::size_t i = 0; i < values.size(); ++i) out_ << (i ? "," : "") << number(values[i]);
  out_ << '\n';
  if (!out_) throw InputError(path_.string(), "", "write failed");
}

CsvTable read_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), "", "cannot open the file for reading");
  CsvTable t;
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
      for (const auto& n : t.names) t.column[n];
      continue;
    }
    const auto cells = split(line);
    if (cells.size() != t.names.size())
      throw InputError(where, "", "expected " + std::to_string(t.names.size()) + " values");
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
