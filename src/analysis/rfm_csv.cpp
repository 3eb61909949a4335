// reader of the RFM tables and their metadata sidecars
#include "analysis/rfm_csv.hpp"

#include <cstdlib>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.hpp"
#include "core/input_file.hpp"
#include "core/records.hpp"

namespace gs::rfm {

namespace {

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
  const std::filesystem::path side = table_meta_path(path);
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
