// `gransim reproduce tapping|rfm`: the sweeps of a study at a budget (resumable), their
// analysis, and a report of the sources' claims beside what the program measured, each with a
// verdict (python3 -m gransim.reproduce writes DIR/report.md, DIR/report.html, DIR/claims.csv)
#pragma once
#include <string>

namespace CLI {
class App;
}

namespace gs {

struct ReproduceOptions {
  std::string study;             ///< "tapping" or "rfm"
  std::string budget = "quick";  ///< smoke, quick, standard, full
  std::string out;               ///< default runs/reproduce-<study>-<budget>
  int jobs = 0;                  ///< runs at a time (0: the number of cores)
  bool run_full = false;         ///< the full budget runs only when asked
  bool report_only = false;      ///< analyse and report what is there, start no run
  bool from_series = false;      ///< the report again from DIR/series alone (a published one)
  bool quiet = false;            ///< no progress display
};

/// the exit code: 0 report written (or the full budget's projection printed), 2 bad input,
/// 4 interrupted (run the same command again), 3/1 a run or the report failed
int reproduce_command(const ReproduceOptions& opt);

/// adds the subcommand to the CLI; returns it so the caller can test whether it was given
CLI::App* add_reproduce_command(CLI::App& app, ReproduceOptions& opt);

}  // namespace gs
