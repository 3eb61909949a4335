// `gransim model bisection|walk|interval|cascade [options] --out DIR`: the thesis' auxiliary
// models (docs/physics.md §5.4, src/models/) as commands writing their CSV files and charts
// (gransim.charts.rfm) into DIR: bisection.csv; walk_l<l>.csv, walk_spm.csv, heating.csv;
// interval.csv; cascade_<kind>.csv; plus model.json with the headline numbers
#pragma once

namespace CLI {
class App;
}

namespace gs {

/// register the `model` subcommand and its four model subcommands on the gransim app. Each
/// runs from its own callback: errors print "gransim: error: …" and end the program with exit
/// code 2 (bad input) or 1 (internal), through CLI::RuntimeError.
void add_model_command(CLI::App& app);

}  // namespace gs
