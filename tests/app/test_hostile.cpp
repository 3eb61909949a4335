// hostile input: every bad scene in tests/app/hostile/ makes `gransim run` exit with code 2, a
// message naming the file (and key), no signal and no output; every bad checkpoint is refused
// by read_checkpoint or restore_simulation with an InputError naming the file
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "binary.hpp"
#include "core/error.hpp"
#include "sim/checkpoint.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;

const fs::path kCorpus = fs::path(GS_SOURCE_DIR) / "tests" / "app" / "hostile";

using testing::Outcome;
using testing::run_binary;

struct Entry {
  std::string file, expect, third;
};

// MANIFEST lines: file<TAB>expected substring<TAB>exit code or stage
std::vector<Entry> manifest(const std::string& name) {
  std::vector<Entry> out;
  std::ifstream in(kCorpus / name);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ls(line);
    Entry e;
    std::getline(ls, e.file, '\t');
    std::getline(ls, e.expect, '\t');
    std::getline(ls, e.third, '\t');
    out.push_back(e);
  }
  return out;
}

fs::path scratch() {
  const fs::path d = fs::temp_directory_path() / ("gs_hostile_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

// the corpus is what the manifests say it is, and it is big enough to mean something
TEST(Hostile, ManifestsListEveryCorpusFile) {
  std::set<std::string> listed;
  for (const auto& e : manifest("MANIFEST")) listed.insert(e.file);
  for (const auto& e : manifest("MANIFEST_CHECKPOINTS")) listed.insert(e.file);
  std::size_t files = 0;
  for (const auto& f : fs::directory_iterator(kCorpus)) {
    const std::string n = f.path().filename().string();
    if (n.starts_with("MANIFEST") || n.ends_with(".py")) continue;
    ++files;
    EXPECT_TRUE(listed.count(n)) << n << " is not in a manifest (run make_corpus.py)";
  }
  EXPECT_GE(files, 40u);
  EXPECT_EQ(files, listed.size());
}

// each bad scene: exit 2, the file and the key named, no signal, no output directory contents
TEST(Hostile, BadScenesExitTwoNamingFileAndKeyWithoutOutput) {
  const fs::path tmp = scratch();
  for (const Entry& e : manifest("MANIFEST")) {
    const fs::path out = tmp / "out";
    fs::remove_all(out);
    const Outcome o =
        run_binary({"run", (kCorpus / e.file).string(), "--out", out.string(), "--quiet"},
                   tmp / "log.txt");
    const int want = e.third.empty() ? 2 : std::stoi(e.third);
    ASSERT_TRUE(o.exited) << e.file << ": killed by signal " << o.code << "\n" << o.output;
    EXPECT_EQ(o.code, want) << e.file << "\n" << o.output;
    if (want != 2) continue;  // accepted on purpose (docs/robustness.md)
    EXPECT_NE(o.output.find(e.file), std::string::npos) << e.file << ": not named\n" << o.output;
    EXPECT_NE(o.output.find(e.expect), std::string::npos)
        << e.file << ": expected '" << e.expect << "' in\n" << o.output;
    EXPECT_TRUE(!fs::exists(out) || fs::is_empty(out)) << e.file << ": left output behind";
  }
  fs::remove_all(tmp);
}

// a refused scene leaves an existing run directory as it was, even with --force
TEST(Hostile, BadSceneWithForceKeepsExistingDirectory) {
  const fs::path tmp = scratch();
  const fs::path out = tmp / "existing";
  fs::create_directories(out);
  std::ofstream(out / "keep.txt") << "keep";
  for (const char* f : {"value_radius_nan.toml", "dt_too_large.toml", "too_many_grains_walls.toml",
                        "syntax_garbage.toml"}) {
    const Outcome o = run_binary(
        {"run", (kCorpus / f).string(), "--out", out.string(), "--force", "--quiet"},
        tmp / "log.txt");
    ASSERT_TRUE(o.exited) << f;
    EXPECT_EQ(o.code, 2) << f << "\n" << o.output;
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& x : fs::directory_iterator(out)) ++n;
    EXPECT_EQ(n, 1u) << f << ": the run directory changed";
    EXPECT_TRUE(fs::exists(out / "keep.txt")) << f;
  }
  fs::remove_all(tmp);
}

// paths that do not exist or are directories
TEST(Hostile, MissingSceneAndDirectoryExitTwo) {
  const fs::path tmp = scratch();
  for (const fs::path& p : {tmp / "no_such_scene.toml", tmp}) {
    const Outcome o =
        run_binary({"run", p.string(), "--out", (tmp / "out").string(), "--quiet"}, tmp / "log");
    ASSERT_TRUE(o.exited) << p;
    EXPECT_EQ(o.code, 2) << p << "\n" << o.output;
    EXPECT_NE(o.output.find(p.string()), std::string::npos) << o.output;
  }
  fs::remove_all(tmp);
}

// each bad checkpoint: InputError naming the file (and the byte offset when reading)
TEST(Hostile, BadCheckpointsAreInputErrors) {
  for (const Entry& e : manifest("MANIFEST_CHECKPOINTS")) {
    const std::string path = (kCorpus / e.file).string();
    try {
      const Checkpoint c = read_checkpoint(path);
      ASSERT_EQ(e.third, "restore") << e.file << " was read";
      restore_simulation(c);
      ADD_FAILURE() << e.file << " was restored";
    } catch (const InputError& err) {
      const std::string m = err.what();
      EXPECT_NE(m.find(path), std::string::npos) << e.file << ": " << m;
      if (e.third == "read") {
        EXPECT_NE(m.find("byte offset"), std::string::npos) << m;
      }
      EXPECT_NE(m.find(e.expect), std::string::npos) << e.file << ": expected '" << e.expect
                                                     << "' in " << m;
    }
  }
  EXPECT_THROW(read_checkpoint((kCorpus / "no_such.gsck").string()), InputError);
  EXPECT_THROW(read_checkpoint(kCorpus.string()), InputError);
}

}  // namespace
}  // namespace gs
