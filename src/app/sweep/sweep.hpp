// `gransim sweep`: one scene run at every value of one or more scene keys, each value its own
// run directory under one sweep directory, as child processes of this binary, with one
// progress display; a sweep can be continued without redoing finished values
#pragma once
#include <string>
#include <vector>

namespace gs {

struct SweepOptions {
  std::string scene;                ///< scene file
  std::vector<std::string> params;  ///< "drive.g_p=4,6,8" (several: every combination)
  std::vector<std::string> sets;    ///< --set overrides shared by every run
  std::string out;                  ///< sweep directory (default runs/<scene name>-<keys>)
  int jobs = 0;                 ///< runs at a time (0: the number of cores; under MPI: 1 per rank)
  int replicas = 1;             ///< runs per value; replica r > 0 has a seed derived from r
  bool force = false;           ///< redo unfinished run directories
  bool quiet = false;           ///< no progress display
  bool allow_unstable = false;  ///< passed on to every run
};

/// one swept key and its values, parsed from "key=v1,v2,…"
struct SweepParam {
  std::string key;                  ///< dotted scene key
  std::vector<std::string> values;  ///< TOML value texts
};

/// parse --param text; throws InputError naming the argument
SweepParam parse_sweep_param(const std::string& text);

/// one run of the sweep: its directory name ("g_p=4", "g_p=4_f=1") and overrides
struct SweepRun {
  std::string name;
  std::vector<std::string> overrides;  ///< "drive.g_p=4", …
};

/// every combination of the values, first parameter slowest
std::vector<SweepRun> sweep_runs(const std::vector<SweepParam>& params);

/// returns the process exit code: 0 all runs completed (or were already), 2 bad input (nothing
/// is started), 3/4/1 the worst exit of a run (unstable, interrupted, failure)
int sweep_command(const SweepOptions& opt);

/// several sweeps as one pool of runs, `jobs` at a time (0: the number of cores): a run of the
/// next sweep starts as soon as a slot is free, so no core idles while the last runs of a
/// sweep finish. Exit codes as sweep_command's; under MPI the sweeps run one after the other
int sweeps_command(const std::vector<SweepOptions>& opts, int jobs);

}  // namespace gs
