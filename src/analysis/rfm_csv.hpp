// reading back the RFM tables (written through a RecordSink, core/records.hpp): one header line
// of column names, then numeric rows; metadata (fit parameters, k_D, …) from NAME.json beside
// NAME.csv, a flat object of numbers (null for a non-finite one). The reader also takes the
// older form's "# key=value" lines above the header.
#pragma once
#include <filesystem>
#include <istream>
#include <map>
#include <string>
#include <vector>

namespace gs::rfm {

/// a CSV file read back: metadata and named columns
struct CsvTable {
  std::map<std::string, double> meta;                 ///< the sidecar's (or "# key=value" lines)
  std::vector<std::string> names;                     ///< header, in order
  std::map<std::string, std::vector<double>> column;  ///< values by column name
  std::string source;                                 ///< the file read

  /// a column by name, or an InputError naming the file and the missing column
  const std::vector<double>& col(const std::string& name) const;
};

/// reads a table the CSV writer of output/ wrote (and its sidecar, table_meta_path); throws
/// gs::InputError naming file and line on error
CsvTable read_csv(const std::filesystem::path& path);
/// the same from a stream (`name` for messages)
CsvTable parse_csv(std::istream& in, const std::string& name);

}  // namespace gs::rfm
