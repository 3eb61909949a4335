// command-line mistakes get a message that names the word or the option, and exit 2
#include <gtest/gtest.h>

#include <filesystem>
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

}  // namespace
}  // namespace gs
