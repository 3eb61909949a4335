// a RecordSink that keeps the observers' rows and documents in memory: the observers measure,
// and these tests see what they would have had written
#pragma once
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/records.hpp"

namespace gs::test {

struct MemoryRecords final : RecordSink {
  struct Table {
    std::vector<std::string> columns;
    RecordMeta meta;
    std::vector<std::vector<double>> rows;
    /// a column by name (throws when there is none)
    std::vector<double> col(const std::string& name) const {
      for (std::size_t c = 0; c < columns.size(); ++c)
        if (columns[c] == name) {
          std::vector<double> v;
          for (const auto& r : rows) v.push_back(r[c]);
          return v;
        }
      throw std::runtime_error("no column " + name);
    }
  };
  mutable std::map<std::string, std::shared_ptr<Table>> tables;
  mutable std::map<std::string, std::string> documents;

  using RecordSink::create;
  std::unique_ptr<RecordTable> create(const std::string& path,
                                      const std::vector<std::string>& columns,
                                      const RecordMeta& meta) const override {
    auto t = std::make_shared<Table>();
    t->columns = columns;
    t->meta = meta;
    tables[path] = t;
    return std::make_unique<Rows>(t, columns.size());
  }
  std::unique_ptr<RecordTable> append(const std::string& path, std::size_t columns) const override {
    auto it = tables.find(path);
    if (it == tables.end()) throw std::runtime_error(path + ": no such table to append to");
    return std::make_unique<Rows>(it->second, columns);
  }
  void document(const std::string& path, const std::string& contents) const override {
    documents[path] = contents;
  }

 private:
  struct Rows final : RecordTable {
    Rows(std::shared_ptr<Table> t, std::size_t n) : table(std::move(t)), columns(n) {}
    void row(const std::vector<double>& values) override {
      if (values.size() != columns) throw std::runtime_error("row of the wrong length");
      table->rows.push_back(values);
    }
    std::shared_ptr<Table> table;
    std::size_t columns;
  };
};

}  // namespace gs::test
