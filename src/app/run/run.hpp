// `gransim run`: build the scene, step it with progress, write the run directory
#pragma once
#include <string>
#include <vector>

namespace gs {

struct RunOptions {
  std::string scene;              ///< scene file
  std::string out;                ///< run directory (default runs/<name>-<time>)
  std::vector<std::string> sets;  ///< --set key=value overrides
  bool force = false;             ///< allow reusing a non-empty run directory
  bool quiet = false;             ///< no progress display
  bool allow_unstable = false;    ///< skip the up-front Δt check
  bool profile = false;           ///< print the wall time per stage of the step at the end
};

/// returns the process exit code (ExitCode)
int run_command(const RunOptions& opt);

struct ResumeOptions {
  std::string dir;     ///< run directory with checkpoint-*.gsck
  bool quiet = false;  ///< no progress display
};

/// continue a run from its newest valid checkpoint: outputs are truncated to the checkpoint
/// and the run goes on exactly as it would have without the interruption
int resume_command(const ResumeOptions& opt);

/// set by SIGINT/SIGTERM/SIGHUP; long loops poll it and stop cleanly
bool stop_requested();
/// the stop signals set stop_requested(); a process started with kParentPidVariable set to its
/// parent's PID (a sweep's run) also gets SIGTERM when that parent ends
void install_stop_handlers();
/// the environment variable a sweep sets in its runs' environment: its own PID
inline constexpr const char* kParentPidVariable = "GS_STOP_WITH_PARENT";

}  // namespace gs
