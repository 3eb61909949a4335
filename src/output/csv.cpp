#include "output/csv.hpp"

#include <stdio_ext.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <utility>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace gs {

namespace {

// the sidecar's text: a flat object in the order given, whole numbers (counts) as JSON
// integers, other numbers with every digit, a non-finite one (no measurement) as null
std::string meta_json(const RecordMeta& meta) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& [k, v] : meta) {
    if (std::isfinite(v) && v == std::trunc(v) && std::abs(v) < 9007199254740992.0)
      j[k] = static_cast<std::int64_t>(v);
    else if (std::isfinite(v))
      j[k] = v;
    else
      j[k] = nullptr;
  }
  return j.dump(2) + '\n';
}

}  // namespace

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& columns,
                     const RecordMeta& meta)
    : path_(path), ncol_(columns.size()) {
  // the sidecar first: a reader that finds the table finds its metadata
  if (!meta.empty()) write_file_atomic(table_meta_path(path).string(), meta_json(meta));
  f_ = std::fopen(path.c_str(), "w");
  if (!f_) throw OutputError(path + ": cannot open the file for writing: " + std::strerror(errno));
  std::string h;
  for (std::size_t k = 0; k < columns.size(); ++k) h += (k ? "," : "") + columns[k];
  h += '\n';
  if (std::fputs(h.c_str(), f_) < 0 || std::fflush(f_) != 0)
    throw OutputError(path + ": write failed: " + std::strerror(errno));
}

CsvWriter CsvWriter::append(const std::string& path, std::size_t columns) {
  CsvWriter w;
  w.f_ = std::fopen(path.c_str(), "a");
  if (!w.f_) throw OutputError(path + ": cannot open the file to append: " + std::strerror(errno));
  w.path_ = path;
  w.ncol_ = columns;
  return w;
}

CsvWriter& CsvWriter::operator=(CsvWriter&& o) noexcept {
  if (this != &o) {
    if (f_) std::fclose(f_);
    f_ = o.f_;
    path_ = std::move(o.path_);
    ncol_ = o.ncol_;
    o.f_ = nullptr;
  }
  return *this;
}

CsvWriter::~CsvWriter() {
  if (f_) std::fclose(f_);
}

void CsvWriter::row(const std::vector<double>& values) {
  if (!f_) throw OutputError(path_ + ": write after an earlier failure");
  if (values.size() != ncol_)
    throw std::logic_error(path_ + ": a row of " + std::to_string(values.size()) +
                           " values for a header of " + std::to_string(ncol_) + " columns");
  char buf[32];
  std::string line;
  line.reserve(values.size() * 16);
  for (std::size_t k = 0; k < values.size(); ++k) {
    // 17 significant digits: the value round-trips exactly
    std::snprintf(buf, sizeof buf, "%.17g", values[k]);
    if (k) line += ',';
    line += buf;
  }
  line += '\n';
  // the size before this row: every earlier row is flushed, so it is exact
  struct stat st {};
  const bool sized = ::fstat(::fileno(f_), &st) == 0;
  if (std::fputs(line.c_str(), f_) < 0 || std::fflush(f_) != 0) {
    const int e = errno;
    // keep every complete row: drop what stdio still holds and cut a partly written line
    __fpurge(f_);
    if (sized && ::ftruncate(::fileno(f_), st.st_size) != 0) {
      // nothing more to do: the message below still names the file
    }
    std::fclose(f_);
    f_ = nullptr;
    throw OutputError(path_ + ": write failed: " + std::strerror(e) +
                      " (every complete row is kept)");
  }
}

namespace {

class CsvTable final : public RecordTable {
 public:
  explicit CsvTable(CsvWriter w) : w_(std::move(w)) {}
  void row(const std::vector<double>& values) override { w_.row(values); }

 private:
  CsvWriter w_;
};

class CsvRecords final : public RecordSink {
 public:
  using RecordSink::create;
  std::unique_ptr<RecordTable> create(const std::string& path,
                                      const std::vector<std::string>& columns,
                                      const RecordMeta& meta) const override {
    return std::make_unique<CsvTable>(CsvWriter(path, columns, meta));
  }
  std::unique_ptr<RecordTable> append(const std::string& path, std::size_t columns) const override {
    return std::make_unique<CsvTable>(CsvWriter::append(path, columns));
  }
  void document(const std::string& path, const std::string& contents) const override {
    write_file_atomic(path, contents);
  }
};

}  // namespace

const RecordSink& csv_records() {
  static const CsvRecords records;
  return records;
}

}  // namespace gs
