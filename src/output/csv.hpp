// append-only CSV series: a header once, one flushed line per record (nothing computed is lost)
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "core/records.hpp"

namespace gs {

class CsvWriter {
 public:
  CsvWriter() = default;
  /// open for writing (truncate) and write the header; throws InputError naming the path
  CsvWriter(const std::string& path, const std::vector<std::string>& columns);
  /// reopen an existing series to append rows (a resumed run; its header is already there)
  static CsvWriter append(const std::string& path, std::size_t columns);
  CsvWriter(CsvWriter&& o) noexcept : f_(o.f_), path_(std::move(o.path_)), ncol_(o.ncol_) {
    o.f_ = nullptr;
  }
  CsvWriter& operator=(CsvWriter&& o) noexcept;
  ~CsvWriter();
  /// one row, flushed; throws std::runtime_error naming the path if the write fails
  void row(const std::vector<double>& values);
  bool is_open() const { return f_ != nullptr; }

 private:
  std::FILE* f_ = nullptr;
  std::string path_;
  std::size_t ncol_ = 0;
};

/// the observers' tables as append-only CSV files (CsvWriter) and their documents written
/// atomically: what a run hands its observers
const RecordSink& csv_records();

}  // namespace gs
