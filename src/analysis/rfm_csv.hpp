// the simple CSV files the RFM analyses write for gransim.charts.rfm: one header line of
// column names, then numeric rows (pandas.read_csv reads them as they are); metadata (fit
// parameters, k_D, …) goes to NAME.json beside NAME.csv, a flat object of numbers (null for a
// non-finite one). The reader also takes the older form's "# key=value" lines above the header.
#pragma once
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace gs::rfm {

/// metadata written to the sidecar NAME.json
using CsvMeta = std::vector<std::pair<std::string, double>>;

/// writes one CSV file, each row flushed as it is written; throws gs::OutputError naming the
/// path when it cannot be written (disk full, read-only), with every complete row kept
class CsvWriter {
 public:
  CsvWriter(const std::filesystem::path& path, const std::vector<std::string>& columns,
            const CsvMeta& meta = {});
  /// one row; its length must match the header
  void row(const std::vector<double>& values);

 private:
  std::filesystem::path path_;
  std::ofstream out_;
  std::size_t columns_ = 0;
  std::uintmax_t complete_ = 0;  ///< bytes up to the end of the last complete line

  void put(const std::string& line);  ///< write, flush, or cut back and throw OutputError
};

/// a CSV file read back: metadata and named columns
struct CsvTable {
  std::map<std::string, double> meta;                 ///< the sidecar's (or "# key=value" lines)
  std::vector<std::string> names;                     ///< header, in order
  std::map<std::string, std::vector<double>> column;  ///< values by column name
  std::string source;                                 ///< the file read

  /// a column by name, or an InputError naming the file and the missing column
  const std::vector<double>& col(const std::string& name) const;
};

/// the metadata sidecar of a CSV file: NAME.csv → NAME.json
std::filesystem::path meta_path(const std::filesystem::path& csv);

/// reads a file written by CsvWriter (and its sidecar); throws gs::InputError naming file and
/// line on error
CsvTable read_csv(const std::filesystem::path& path);
/// the same from a stream (`name` for messages)
CsvTable parse_csv(std::istream& in, const std::string& name);

}  // namespace gs::rfm
