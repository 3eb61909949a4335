// observers measure, writers write: an observer hands its rows to a RecordTable and its
// summaries to a RecordSink, and never opens a file itself. The run gives the CSV writer of
// output/ (output/csv.hpp, csv_records()); a test can keep the rows in memory.
#pragma once
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace gs {

/// one table of numbers (a CSV file for a run): each row is stored before row() returns
class RecordTable {
 public:
  virtual ~RecordTable() = default;
  virtual void row(const std::vector<double>& values) = 0;
};

/// numbers that describe a whole table (a histogram's binning, a fit's parameters), in order;
/// beside NAME.csv they go to the flat JSON object NAME.json (table_meta_path)
using RecordMeta = std::vector<std::pair<std::string, double>>;

/// where a table's metadata goes: NAME.csv → NAME.json (the readers look there)
inline std::filesystem::path table_meta_path(const std::filesystem::path& table) {
  std::filesystem::path p = table;
  p.replace_extension(".json");
  return p;
}

/// where an observer's tables and documents go, named by path in the run directory
class RecordSink {
 public:
  virtual ~RecordSink() = default;
  /// a new table with these columns and metadata (replacing any earlier one of that name)
  virtual std::unique_ptr<RecordTable> create(const std::string& path,
                                              const std::vector<std::string>& columns,
                                              const RecordMeta& meta) const = 0;
  /// a new table without metadata
  std::unique_ptr<RecordTable> create(const std::string& path,
                                      const std::vector<std::string>& columns) const {
    return create(path, columns, {});
  }
  /// continue a table a checkpointed run began (its header is already there)
  virtual std::unique_ptr<RecordTable> append(const std::string& path,
                                              std::size_t columns) const = 0;
  /// a whole small document (a JSON summary), replaced at once
  virtual void document(const std::string& path, const std::string& contents) const = 0;
};

}  // namespace gs
