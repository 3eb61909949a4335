#pragma once
namespace gs {
/// parse the command line, run the chosen subcommand, return the process exit code
int run_cli(int argc, char** argv);
}  // namespace gs
