// the raw tables of the Random Force Model observers that the analysis reads back: histograms
// with their binning and every sample count (so fits can be redone on the counts), the binning
// and totals as the table's metadata (read back by analysis/rfm_csv.hpp)
#pragma once
#include <filesystem>

#include "analysis/rfm_hist.hpp"
#include "core/records.hpp"

namespace gs::rfm {

/// columns lo, hi, x, count, P, P_err; metadata scale (0 linear, 1 log), lo, hi, n, total,
/// underflow, overflow
void write_histogram_raw(const RecordSink& sink, const std::filesystem::path& path,
                         const Histogram& h);
/// the histogram written by write_histogram_raw, counts and totals restored exactly; throws
/// gs::InputError naming the file when it is not such a file
Histogram read_histogram_raw(const std::filesystem::path& path);

}  // namespace gs::rfm
