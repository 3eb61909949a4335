#include "app/cli.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <new>
#include <string>
#include <vector>

#include "app/analyze/analyze.hpp"
#include "app/analyze/rfm_models.hpp"
#include "app/cli_checks.hpp"
#include "app/render/render_cmd.hpp"
#include "app/reproduce/reproduce.hpp"
#include "app/run/run.hpp"
#include "app/study/study.hpp"
#include "app/sweep/sweep.hpp"
#include "app/version.hpp"
#include "core/error.hpp"

namespace gs {

namespace {

// Levenshtein distance, for "did you mean"
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

}  // namespace

int run_cli(int argc, char** argv) {
  CLI::App app{"gransim: headless 2D granular dynamics (polygon DEM tapping, Random Force Model)",
               "gransim"};
  app.set_version_flag("--version", version_text());
  app.require_subcommand(1);

  // run
  RunOptions ro;
  auto* run = app.add_subcommand("run", "run a scene and write a run directory");
  run->add_option("scene", ro.scene, "scene file (TOML, see docs/scene-format.md)")->required();
  run->add_option("-o,--out", ro.out, "run directory (default runs/<name>-<time>)");
  run->add_option("--set", ro.sets, "override a scene key, e.g. --set drive.g_p=8 (repeatable)");
  run->add_flag("--force", ro.force, "reuse a non-empty run directory (its contents are removed)");
  run->add_flag("-q,--quiet", ro.quiet, "no progress display");
  run->add_flag("--allow-unstable", ro.allow_unstable, "skip the up-front time-step check");
  run->add_flag("--profile", ro.profile,
                "print the wall time of each stage of the step at the end (also in run.json)");

  // resume: continue an interrupted run from its newest checkpoint
  ResumeOptions rso;
  auto* resume = app.add_subcommand(
      "resume", "continue an interrupted run from its newest valid checkpoint (bitwise)");
  resume->add_option("dir", rso.dir, "run directory (holds checkpoint-*.gsck)")->required();
  resume->add_flag("-q,--quiet", rso.quiet, "no progress display");

  // sweep: one run directory per value of the swept keys, as child processes
  SweepOptions so;
  auto* sweep =
      app.add_subcommand("sweep", "run a scene at several values of scene keys, in parallel");
  sweep->add_option("scene", so.scene, "scene file (TOML)")->required();
  sweep
      ->add_option("--param", so.params,
                   "swept key and values, e.g. --param drive.g_p=4,6,8 (repeat for a grid)")
      ->required();
  sweep->add_option("-o,--out", so.out, "sweep directory (default runs/<name>-sweep-<keys>)");
  sweep->add_option("--set", so.sets, "override a scene key in every run (repeatable)");
  sweep
      ->add_option("-j,--jobs", so.jobs,
                   "runs at a time (default: the number of cores; under mpirun: 1 per rank)")
      ->check(cli_check::non_negative);
  sweep
      ->add_option("--replicas", so.replicas,
                   "runs per value; replica r > 0 gets a seed hashed from the scene's and r, "
                   "in <name>_rep=<r> (default 1)")
      ->check(cli_check::positive);
  sweep->add_flag("--force", so.force, "redo unfinished runs (completed runs are always kept)");
  sweep->add_flag("-q,--quiet", so.quiet, "no progress display");
  sweep->add_flag("--allow-unstable", so.allow_unstable, "skip the up-front time-step check");

  // analyze: the tapping statistics and charts of runs and sweeps
  AnalyzeOptions ao;
  auto* analyze = app.add_subcommand(
      "analyze", "statistics and charts of runs and sweeps (tapping study or Random Force Model)");
  analyze->add_option("dirs", ao.dirs,
                      "run or sweep directories, or plain φ series FILE[:label] (a CSV with a "
                      "phi column, any case; ',' ';' tab or blank separated)");
  analyze->add_option("--series", ao.series,
                      "a plain φ series PROTOCOL:CONTROL:FILE (a CSV with a phi column; "
                      "repeatable), e.g. negative_g:6:g6.csv");
  analyze->add_option("--manifest", ao.manifest,
                      "a CSV listing plain series: file,protocol,control[,label][,test_area]");
  analyze
      ->add_option("--test-area", ao.test_area,
                   "area of the test region of plain series, m² (V_g = area·φ̄_ref); "
                   "without it, φ statistics only (no β̂, no quadron fit)")
      ->check(cli_check::positive);
  analyze->add_option(
      "-o,--out", ao.out,
      "analysis folder (default DIR/analysis, FILE's folder/<stem>_analysis; needed "
      "for several DIRs or series)");
  analyze
      ->add_option("--discard", ao.discard, "transient taps to drop (default: output.discard_taps)")
      ->check(cli_check::non_negative);
  analyze->add_flag("--discard-auto", ao.discard_auto,
                    "per run, drop the larger of --discard and the transient the marginal "
                    "standard error rule (MSER-5) finds");
  analyze->add_option("--reference", ao.reference,
                      "reference run label, e.g. negative_g_6 (default: g_p nearest 6)");
  analyze->add_option("--reference2", ao.reference2, "second reference run label");
  analyze->add_flag(
      "--no-charts", [&](std::int64_t) { ao.charts = false; }, "write CSV/JSON only");
  analyze->add_flag("-q,--quiet", ao.quiet, "no summary table and no progress display");

  // study: speed against accuracy and the stability map (app/study/study.cpp)
  StudyOptions sto;
  auto* study = add_study_command(app, sto);

  // render and movie (app/render/render_cmd.cpp)
  auto render_cmds = add_render_commands(app);

  // reproduce: a study's sweeps, analysis and report of claims (app/reproduce/)
  ReproduceOptions rpo;
  auto* reproduce = add_reproduce_command(app, rpo);

  // model: the thesis' auxiliary models, run from their own callbacks (app/analyze/rfm_models.cpp)
  add_model_command(app);

  // an unknown command word is named, with the nearest command
  if (argc > 1 && argv[1][0] != '-') {
    const std::string word = argv[1];
    std::string best;
    std::size_t best_d = std::string::npos;
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
      known = known || sub->get_name() == word;
      const std::size_t d = edit_distance(word, sub->get_name());
      if (d < best_d) best_d = d, best = sub->get_name();
    }
    if (!known) {
      std::fprintf(stderr, "gransim: '%s' is not a command%s (gransim --help lists them)\n",
                   word.c_str(),
                   best_d <= 3 ? (std::string("; did you mean '") + best + "'?").c_str() : "");
      return kExitBadInput;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    // a `model` command's outcome, thrown from its callback with gransim's exit code
    return e.get_exit_code();
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitBadInput;
  }
  try {
    if (*run) return run_command(ro);
    if (*resume) return resume_command(rso);
    if (auto code = dispatch_render_commands(*render_cmds)) return *code;
    if (*sweep) return sweep_command(so);
    if (*analyze) return analyze_command(ao);
    if (*study) return study_command(sto);
    if (*reproduce) return reproduce_command(rpo);
  } catch (const InputError& e) {
    std::fprintf(stderr, "gransim: error: %s\n", e.what());
    return kExitBadInput;
  } catch (const OutputError& e) {
    std::fprintf(stderr, "gransim: cannot write output: %s\n", e.what());
    return kExitOutput;
  } catch (const std::filesystem::filesystem_error& e) {
    // a folder that cannot be created or listed, a file that cannot be replaced
    std::fprintf(stderr, "gransim: file system error: %s\n", e.what());
    return kExitOutput;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr,
                 "gransim: out of memory (the input asks for more than this machine has)\n");
    return kExitFailure;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gransim: internal error: %s\n", e.what());
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace gs
