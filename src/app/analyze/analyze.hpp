// `gransim analyze`: the tapping study's statistics over run and sweep directories (docs/physics.md
// §2.6): finds the tapping runs (taps.csv), reads protocol and control value from each run's
// scene.toml, writes the analysis (gs::analyze_tapping) and draws the charts with
// gransim.charts.tapping and gransim.charts.taprun
#pragma once
#include <string>
#include <vector>

#include "app/progress.hpp"

namespace gs {

struct AnalyzeOptions {
  std::vector<std::string> dirs;   ///< run directories and/or sweep directories
  std::vector<std::string> files;  ///< plain φ series FILE[:label] (positional arguments that
                                   ///< name files: split from dirs by analyze_command)
  std::string out;                 ///< analysis folder (default DIR/analysis for one DIR)
  int discard = -1;           ///< transient taps to drop (−1: the scenes' output.discard_taps)
  bool discard_auto = false;  ///< per run, the larger of discard and the MSER-5 cut
  std::string reference;      ///< reference run label (default: the library's choice)
  std::string reference2;     ///< second reference label
  bool charts = true;         ///< draw the charts (gransim.charts)
  bool quiet = false;         ///< no summary table and no progress display
  /// the progress display of an analysis that takes more than a couple of seconds: one line
  /// redrawn on a terminal, a plain line every 5 s otherwise (tests give it a clock)
  ProgressSettings progress{{}, -1, nullptr, 2.0, 5.0, 2.0};
  // plain φ series from anywhere (experiments, other simulators): no run directory needed
  std::vector<std::string> series;  ///< "PROTOCOL:CONTROL:FILE" (a CSV with a phi column)
  std::string manifest;             ///< a CSV: file,protocol,control[,label][,test_area]
  double test_area = -1.0;          ///< area of the test region, m² (V_g = test_area·φ̄_ref)
};

/// a plain series with where it came from
struct PlainSeries {
  std::string file;      ///< the CSV
  std::string protocol;  ///< protocol or label of the experiment; "" when not known
  double control = 0.0;  ///< its control value; NaN when not known
  std::string label;     ///< "" = <protocol>_<control>
};

/// the positional arguments that are plain series (FILE or FILE:label naming a file), in
/// order; the others (directories) are left in `dirs`. A missing file that looks like a series
/// (FILE:label, *.csv, *.txt, *.dat) is an InputError naming the argument.
std::vector<std::string> split_series_arguments(std::vector<std::string>& dirs);

/// the series given as files, by --series and by --manifest, checked (files exist, controls
/// are numbers, one test area) and labelled uniquely (two series with one protocol and control
/// are told apart by their file names); test_area is set from the manifest when given there.
/// InputError names the argument or the manifest's file:line and column.
std::vector<PlainSeries> plain_series(const AnalyzeOptions& opt, double& test_area);

/// one tapping run found on disk
struct FoundTapRun {
  std::string dir;       ///< run directory
  std::string protocol;  ///< "negative_g" or "rotating_g"
  double control = 0.0;  ///< g_p (units of g) or f (Hz)
  std::string status;    ///< run.json status ("" when absent)
};

/// the tapping runs in a directory: itself when it holds taps.csv, else its subdirectories
/// that do (sorted by protocol, control, name); throws InputError when there are none
std::vector<FoundTapRun> find_tap_runs(const std::string& dir);

/// returns the process exit code (0 also when only the charts could not be drawn)
int analyze_command(const AnalyzeOptions& opt);

}  // namespace gs
