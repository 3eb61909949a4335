// command-line mistakes get a message that names the word or the option, and exit 2
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;
using testing::run_binary;

fs::path log_file() { return fs::temp_directory_path() / ("gs-cli-" + std::to_string(::getpid())); }

TEST(CliMessages, AnUnknownCommandIsNamedWithTheNearestOne) {
  auto o = run_binary({"rn", "scenes/demo.toml"}, log_file());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.output.find("'rn' is not a command; did you mean 'run'?"), std::string::npos)
      << o.output;
  o = run_binary({"reproduse", "tapping"}, log_file());
  EXPECT_NE(o.output.find("did you mean 'reproduce'?"), std::string::npos) << o.output;
  o = run_binary({"qqqqqqqqqq"}, log_file());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.output.find("'qqqqqqqqqq' is not a command"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("did you mean"), std::string::npos) << o.output;
  fs::remove(log_file());
}

TEST(CliMessages, MovieValuesOutOfRangeAreErrorsNotDefaults) {
  for (const auto& bad : std::vector<std::vector<std::string>>{
           {"--fps", "0"}, {"--fps", "-5"}, {"--crf", "-1"}, {"--crf", "52"}}) {
    std::vector<std::string> args = {"movie", "no-such-run"};
    args.insert(args.end(), bad.begin(), bad.end());
    const auto o = run_binary(args, log_file());
    EXPECT_EQ(o.code, 2) << bad[0] << " " << bad[1] << "\n" << o.output;
    EXPECT_NE(o.output.find(bad[0]), std::string::npos) << o.output;
  }
  fs::remove(log_file());
}

// a message names what the user wrote and what to change: a bound as it is written (never the
// 309 digits of the largest double), a model's flag (never its internal key), a file that is
// not a run directory as a file
TEST(CliMessages, MessagesNameTheFlagAndTheBoundAsWritten) {
  const fs::path tmp = testing::fresh_test_dir("gs-cli");
  auto o = run_binary({"analyze", "--discard", "-1", "x"}, log_file());
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find("--discard"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find(">= 0"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("17976931348623157"), std::string::npos) << o.output;
  o = run_binary({"sweep", "x.toml", "--param", "a=1", "--replicas", "0"}, log_file());
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_LT(o.output.size(), 300u) << o.output;
  // a cascade's D_f window beyond its grid names --fit-hi, not fit_df's k_hi
  o = run_binary({"model", "cascade", "--levels", "4", "--realisations", "2", "--fit-lo", "100",
                  "--fit-hi", "200", "--out", (tmp / "c").string(), "--no-charts", "-q"},
                 log_file());
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find("--fit-hi"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("k_hi"), std::string::npos) << o.output;
  // a model's own check names the flag
  o = run_binary({"model", "walk", "--noise", "-1", "--out", (tmp / "w").string(), "-q"},
                 log_file());
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find("--noise"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("key '"), std::string::npos) << o.output;
  // a manifest's negative test area is named as such, not as missing
  std::ofstream(tmp / "s.csv") << "phi\n0.8\n";
  std::ofstream(tmp / "m.csv") << "file,protocol,control,test_area\ns.csv,negative_g,6,-0.1\n";
  o = run_binary({"analyze", "--manifest", (tmp / "m.csv").string(), "-q"}, log_file());
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find("test_area"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("-0.1"), std::string::npos) << o.output;
  fs::remove_all(tmp);
  fs::remove(log_file());
}

}  // namespace
}  // namespace gs
