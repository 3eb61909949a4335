// the simple CSV files the RFM analyses write for tools/charts_rfm.py: one header line of
// column names, then numeric rows (pandas.read_csv reads them as they are); metadata (fit
// parameters, k_D, …) goes to NAME.json beside NAME.csv, a flat object of numbers (null for a
// non-finite one). The reader also takes the older form's "# key=value" lines above the header.
#pragma once
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace gs::rfm {

/// metadata written to the sidecar NAME.json
using CsvMeta = std::vector<std::pair<std::string, double>>;

/// writes one CSV file; throws gs::InputError naming the path when it cannot be written
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
};

/// a CSV file read back: metadata and named columns
struct CsvTable {
  std::map<std::string, double> meta;                 ///< the sidecar's (or "# key=value" lines)
  std::vector<std::string> names;                     ///< header, in order
  std::map<std::string, std::vector<double>> column;  ///< values by column name
};

/// the metadata sidecar of a CSV file: NAME.csv → NAME.json
std::filesystem::path meta_path(const std::filesystem::path& csv);

/// reads a file written by CsvWriter (and its sidecar); throws gs::InputError naming file and
/// line on error
CsvTable read_csv(const std::filesystem::path& path);

}  // namespace gs::rfm
