// the one CSV writer: a header once, one flushed line per record (nothing computed is lost),
// every number in %.17g (it reads back to the same double); a table's metadata goes to the flat
// JSON object NAME.json beside NAME.csv (core/records.hpp)
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "core/records.hpp"

namespace gs {

class CsvWriter {
 public:
  CsvWriter() = default;
  /// open for writing (truncate), write the metadata sidecar when there is metadata, then the
  /// header; throws OutputError naming the path
  CsvWriter(const std::string& path, const std::vector<std::string>& columns,
            const RecordMeta& meta = {});
  /// reopen an existing series to append rows (a resumed run; its header is already there)
  static CsvWriter append(const std::string& path, std::size_t columns);
  CsvWriter(CsvWriter&& o) noexcept : f_(o.f_), path_(std::move(o.path_)), ncol_(o.ncol_) {
    o.f_ = nullptr;
  }
  CsvWriter& operator=(CsvWriter&& o) noexcept;
  ~CsvWriter();
  /// one row, flushed; throws OutputError naming the path if the write fails, std::logic_error
  /// if its length is not the header's
  void row(const std::vector<double>& values);
  bool is_open() const { return f_ != nullptr; }

 private:
  std::FILE* f_ = nullptr;
  std::string path_;
  std::size_t ncol_ = 0;
};

/// the observers' and analyses' tables as CSV files (CsvWriter) and their documents written
/// atomically: what a run hands its observers, what `gransim analyze` writes through
const RecordSink& csv_records();

}  // namespace gs
