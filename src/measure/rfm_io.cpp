// raw histogram files of the RFM observers (counts, binning, totals)
#include "measure/rfm_io.hpp"

#include <cmath>
#include <string>

#include "analysis/rfm_csv.hpp"
#include "core/error.hpp"

namespace gs::rfm {

void write_histogram_raw(const RecordSink& sink, const std::filesystem::path& path,
                         const Histogram& h) {
  const Binning& b = h.binning();
  const auto w = sink.create(path.string(), {"lo", "hi", "x", "count", "P", "P_err"},
                             {{"scale", b.scale == Binning::Scale::log ? 1.0 : 0.0},
                              {"lo", b.lo},
                              {"hi", b.hi},
                              {"n", static_cast<double>(b.n)},
                              {"total", h.total()},
                              {"underflow", h.underflow()},
                              {"overflow", h.overflow()}});
  for (const HistBin& x : h.bins()) w->row({x.lo, x.hi, x.x, x.count, x.p, x.p_err});
}

Histogram read_histogram_raw(const std::filesystem::path& path) {
  const CsvTable t = read_csv(path);
  const std::string where = path.string();
  auto meta = [&](const char* k) {
    auto it = t.meta.find(k);
    if (it == t.meta.end())
      throw InputError(where, k,
                       "missing from the metadata (" + table_meta_path(path).filename().string() +
                           " beside it): not a raw histogram");
    return it->second;
  };
  const int n = static_cast<int>(meta("n"));
  const Binning b = meta("scale") == 1.0 ? Binning::log(meta("lo"), meta("hi"), n)
                                         : Binning::linear(meta("lo"), meta("hi"), n);
  Histogram h(b);
  const auto c = t.column.find("count");
  if (c == t.column.end() || static_cast<int>(c->second.size()) != n)
    throw InputError(where, "count", "expected a count column with " + std::to_string(n) + " rows");
  // refill: every count at its bin centre, under- and overflow just outside the range
  for (int i = 0; i < n; ++i) {
    const double k = c->second[static_cast<std::size_t>(i)];
    if (!(k >= 0.0) || k != std::floor(k))
      throw InputError(where, "count", "row " + std::to_string(i + 1) + ": not a count");
    for (double q = 0; q < k; ++q) h.add(b.centre(i));
  }
  const double below = b.scale == Binning::Scale::log ? 0.5 * b.lo : b.lo - 1.0;
  for (double q = 0; q < meta("underflow"); ++q) h.add(below);
  for (double q = 0; q < meta("overflow"); ++q) h.add(b.hi * 2.0 + 1.0);
  if (h.total() != meta("total"))
    throw InputError(where, "total", "counts do not add up to the recorded total");
  return h;
}

}  // namespace gs::rfm
