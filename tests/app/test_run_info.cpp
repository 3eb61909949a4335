// what a run directory says about itself (run.json read with nlohmann-json, older files with
// bare nan too) and the one helper that starts child processes
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "app/run/run_info.hpp"
#include "app/subprocess.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("gs_test_run_info_" + std::to_string(getpid()) + "_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(RunInfo, FieldsOfRunJsonAndOfOlderFilesWithBareNan) {
  const std::string now = "{\n  \"status\": \"completed\",\n  \"rate\": null,\n  \"taps\": 12\n}\n";
  EXPECT_EQ(json_string_field(now, "status"), "completed");
  EXPECT_EQ(json_number_field(now, "taps"), 12.0);
  EXPECT_TRUE(std::isnan(json_number_field(now, "rate").value_or(0.0)));
  EXPECT_FALSE(json_number_field(now, "absent"));
  EXPECT_FALSE(json_number_field(now, "status"));
  // written before non-finite numbers became null: still read, the nan as NaN
  const std::string old = "{\n  \"status\": \"interrupted\",\n  \"rate\": -nan,\n  \"t\": 1.5\n}\n";
  EXPECT_EQ(json_string_field(old, "status"), "interrupted");
  EXPECT_TRUE(std::isnan(json_number_field(old, "rate").value_or(0.0)));
  EXPECT_EQ(json_number_field(old, "t"), 1.5);
  // a nested "status" is not the run's
  EXPECT_FALSE(json_string_field("{\"scene\": {\"status\": \"completed\"}}", "status"));
  EXPECT_FALSE(json_string_field("not json", "status"));
}

TEST(RunInfo, RunStatusOfADirectory) {
  const fs::path d = scratch("status");
  EXPECT_EQ(run_status(d.string()), "");
  std::ofstream(d / "run.json")
      << "{\n  \"program\": \"gransim\",\n  \"status\": \"unstable\"\n}\n";
  EXPECT_EQ(run_status(d.string()), "unstable");
  std::ofstream(d / "run.json") << "{\n  \"program\": \"gransim\"\n}\n";
  EXPECT_EQ(run_status(d.string()), "unknown");
  fs::remove_all(d);
}

TEST(Subprocess, ChildOutputIntoALogAndAClearErrorWhenItCannotStart) {
  const fs::path d = scratch("spawn");
  const std::string log = (d / "child.log").string();
  ChildSetup setup;
  setup.stdin_null = true;
  setup.log = log;
  const std::vector<std::string> env{"GS_CHILD_WORD=hello"};
  setup.environment = &env;
  pid_t pid = start_process({"/bin/sh", "-c", "echo $GS_CHILD_WORD; echo oops >&2; exit 3"}, setup);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  EXPECT_EQ(WEXITSTATUS(status), 3);
  std::ifstream in(log);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "hello\noops\n");
  // appended, not truncated, when asked
  setup.append_log = true;
  pid = start_process({"/bin/sh", "-c", "echo again"}, setup);
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  std::ifstream again(log);
  text.assign(std::istreambuf_iterator<char>(again), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "hello\noops\nagain\n");
  try {
    start_process({(d / "no-such-program").string()}, setup);
    ADD_FAILURE() << "started a program that does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-program"), std::string::npos) << e.what();
  }
  EXPECT_EQ(run_process({"/bin/sh", "-c", "exit 4"}), "/bin/sh exited with 4");
  fs::remove_all(d);
}

}  // namespace
}  // namespace gs
