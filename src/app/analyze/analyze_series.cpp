// `gransim analyze --series … / --manifest …`: φ series that are not gransim runs (an
// experiment's, another simulator's), described on the command line or in a small CSV
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "app/analyze/analyze.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"

namespace gs {

namespace fs = std::filesystem;

namespace {

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  const auto b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, sep)) out.push_back(trim(cell));
  if (!line.empty() && line.back() == sep) out.emplace_back();
  return out;
}

double number(const std::string& text, const std::string& where, const std::string& key) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v))
    throw InputError(where, key, "not a finite number: '" + text + "'");
  return v;
}

void check_file(const std::string& file, const std::string& where, const std::string& key) {
  // a FIFO, a device or a huge file is named as such
  try {
    check_input_file(file, "series file");
  } catch (const InputError& e) {
    throw InputError(where, key, e.what());
  }
}

bool is_file(const std::string& path) {
  std::error_code ec;
  return !path.empty() && fs::exists(path, ec) && !fs::is_directory(path, ec);
}

// FILE or FILE:label → the file and its label ("" when none)
std::pair<std::string, std::string> file_and_label(const std::string& arg) {
  if (is_file(arg)) return {arg, ""};
  const auto colon = arg.rfind(':');
  if (colon != std::string::npos && colon > 0) return {arg.substr(0, colon), arg.substr(colon + 1)};
  return {arg, ""};
}

bool looks_like_series(const std::string& file) {
  const std::string ext = fs::path(file).extension().string();
  return ext == ".csv" || ext == ".CSV" || ext == ".txt" || ext == ".dat" || ext == ".tsv";
}

// the label a series is known by in the analysis
std::string effective_label(const PlainSeries& p) {
  if (!p.label.empty()) return p.label;
  std::ostringstream c;
  c << p.control;
  return (p.protocol.empty() ? std::string("run") : p.protocol) + "_" + c.str();
}

// series labelled automatically that share a label (one protocol and control, or one file
// name): each named after its file as well, its stem first, else its path as given
void make_labels_unique(std::vector<PlainSeries>& series, const std::vector<bool>& automatic) {
  for (int pass = 0; pass < 2; ++pass) {
    std::map<std::string, int> uses;
    for (const auto& p : series) ++uses[effective_label(p)];
    for (std::size_t i = 0; i < series.size(); ++i) {
      PlainSeries& p = series[i];
      if (!automatic[i] || uses[effective_label(p)] < 2) continue;
      const std::string name = pass == 0 ? fs::path(p.file).stem().string() : p.file;
      p.label = p.protocol.empty()
                    ? name
                    : effective_label(PlainSeries{"", p.protocol, p.control, ""}) + "@" + name;
    }
  }
}

}  // namespace

std::vector<std::string> split_series_arguments(std::vector<std::string>& dirs) {
  std::vector<std::string> files, rest;
  for (const auto& arg : dirs) {
    std::error_code ec;
    if (fs::is_directory(arg, ec)) {
      rest.push_back(arg);
      continue;
    }
    const auto [file, label] = file_and_label(arg);
    if (is_file(file)) {
      files.push_back(arg);
    } else if (!label.empty() || looks_like_series(file)) {
      throw InputError(arg, "FILE", "no such file (a plain series is FILE or FILE:label)");
    } else {
      rest.push_back(arg);  // find_tap_runs names it: not a directory
    }
  }
  dirs = rest;
  return files;
}

std::vector<PlainSeries> plain_series(const AnalyzeOptions& opt, double& test_area) {
  std::vector<PlainSeries> out;
  std::vector<bool> automatic;  // labelled by the program, not by the user
  // positional FILE[:label]: a series of unknown protocol and control, named by its label or
  // its file's stem
  for (const auto& arg : opt.files) {
    const auto [file, label] = file_and_label(arg);
    PlainSeries p;
    p.file = file;
    p.control = std::nan("");
    p.label = label.empty() ? fs::path(file).stem().string() : label;
    check_file(p.file, arg, "FILE");
    out.push_back(p);
    automatic.push_back(label.empty());
  }
  // --series PROTOCOL:CONTROL:FILE
  for (const auto& text : opt.series) {
    const auto a = text.find(':'), b = a == std::string::npos ? a : text.find(':', a + 1);
    if (b == std::string::npos || a == 0)
      throw InputError("--series " + text, "--series", "expected PROTOCOL:CONTROL:FILE");
    PlainSeries p;
    p.protocol = text.substr(0, a);
    p.control = number(text.substr(a + 1, b - a - 1), "--series " + text, "CONTROL");
    p.file = text.substr(b + 1);
    check_file(p.file, "--series " + text, "FILE");
    out.push_back(p);
    automatic.push_back(true);
  }
  // --manifest: a CSV with a header naming file, protocol, control and optionally label and
  // test_area; files are relative to the manifest
  if (!opt.manifest.empty()) {
    check_input_file(opt.manifest, "manifest");
    std::ifstream in(opt.manifest);
    if (!in) throw InputError(opt.manifest, "--manifest", "cannot be read (not a regular file)");
    const fs::path base = fs::path(opt.manifest).parent_path();
    std::string line;
    std::vector<std::string> head;
    int lineno = 0;
    int c_file = -1, c_proto = -1, c_control = -1, c_label = -1, c_area = -1;
    while (std::getline(in, line)) {
      ++lineno;
      if (lineno == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
      if (trim(line).empty() || trim(line)[0] == '#') continue;
      const std::string where = opt.manifest + ":" + std::to_string(lineno);
      const auto cells = split(line, ',');
      if (head.empty()) {
        head = cells;
        for (std::size_t i = 0; i < head.size(); ++i) {
          const int k = static_cast<int>(i);
          if (head[i] == "file") c_file = k;
          if (head[i] == "protocol") c_proto = k;
          if (head[i] == "control") c_control = k;
          if (head[i] == "label") c_label = k;
          if (head[i] == "test_area") c_area = k;
        }
        for (const auto& [c, name] : {std::pair{c_file, "file"}, std::pair{c_proto, "protocol"},
                                      std::pair{c_control, "control"}})
          if (c < 0) throw InputError(where, name, std::string("missing column '") + name + "'");
        continue;
      }
      auto cell = [&](int c) -> std::string {
        if (c >= static_cast<int>(cells.size()))
          throw InputError(where, head[static_cast<std::size_t>(c)], "row has no value here");
        return cells[static_cast<std::size_t>(c)];
      };
      PlainSeries p;
      p.file = (base / cell(c_file)).string();
      p.protocol = cell(c_proto);
      if (p.protocol.empty()) throw InputError(where, "protocol", "is empty");
      p.control = number(cell(c_control), where, "control");
      if (c_label >= 0) p.label = cell(c_label);
      if (c_area >= 0 && !cell(c_area).empty()) {
        const double a = number(cell(c_area), where, "test_area");
        if (!(a > 0.0))
          throw InputError(where, "test_area", "must be an area > 0 m² (got " + cell(c_area) + ")");
        if (test_area > 0.0 && std::abs(a - test_area) > 1e-12 * a)
          throw InputError(where, "test_area",
                           "differs from the other rows' (one test region for the study)");
        test_area = a;
      }
      check_file(p.file, where, "file");
      out.push_back(p);
      automatic.push_back(p.label.empty());
    }
    if (head.empty()) throw InputError(opt.manifest, "--manifest", "no header row");
  }
  if (out.empty()) throw InputError("", "--series", "no series given");
  make_labels_unique(out, automatic);
  return out;
}

}  // namespace gs
