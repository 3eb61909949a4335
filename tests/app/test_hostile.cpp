// hostile input: every case of tests/app/hostile/MANIFEST (bad scenes, CSV series, state files,
// locked and occupied directories, FIFOs, sizes that would hang or exhaust memory) ends with
// its exit code, no signal, no internal error, within 10 s of CPU time (a minute of wall time
// for what would block); every bad checkpoint is refused by
// read_checkpoint or restore_simulation with an InputError naming the file
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
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

// MANIFEST_CHECKPOINTS lines: file<TAB>expected substring<TAB>stage
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

// MANIFEST lines: file<TAB>class<TAB>exit code<TAB>substring<TAB>command
struct Case {
  std::string file, cls, expect, command;
  int code = 0;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  std::ifstream in(kCorpus / "MANIFEST");
  std::string line, code;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ls(line);
    Case c;
    std::getline(ls, c.file, '\t');
    std::getline(ls, c.cls, '\t');
    std::getline(ls, code, '\t');
    std::getline(ls, c.expect, '\t');
    std::getline(ls, c.command, '\t');
    c.code = std::stoi(code);
    out.push_back(c);
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
  for (const auto& c : cases()) listed.insert(c.file);
  for (const auto& e : manifest("MANIFEST_CHECKPOINTS")) listed.insert(e.file);
  listed.erase("-");
  std::size_t files = 0;
  for (const auto& f : fs::directory_iterator(kCorpus)) {
    const std::string n = f.path().filename().string();
    if (n.starts_with("MANIFEST") || n.ends_with(".py") || f.is_directory()) continue;
    ++files;
    EXPECT_TRUE(listed.count(n)) << n << " is not in a manifest (run make_corpus.py)";
  }
  EXPECT_GE(cases().size(), 170u);
  EXPECT_EQ(files, listed.size());
}

// the placeholders of the MANIFEST's commands, made afresh for every case
class Sandbox {
 public:
  explicit Sandbox(const fs::path& tmp) : tmp_(tmp) {}
  ~Sandbox() { release(); }

  std::vector<std::string> args(const Case& c) {
    release();
    for (const char* d : {"out", "out.png", "out.mp4", "run", "run_gap", "locked", "locked_empty",
                          "nonempty", "same.png"})
      fs::remove_all(tmp_ / d);
    std::vector<std::string> out;
    std::istringstream words(c.command);
    for (std::string w; words >> w;) out.push_back(fill(w, c));
    return out;
  }

 private:
  std::string fill(std::string w, const Case& c) {
    auto replace = [&](const std::string& key, const std::function<std::string()>& make) {
      const std::string k = "{" + key + "}";
      for (std::size_t p; (p = w.find(k)) != std::string::npos;) w.replace(p, k.size(), make());
    };
    replace("file", [&] { return (kCorpus / c.file).string(); });
    replace("corpus", [&] { return kCorpus.string(); });
    replace("out", [&] { return (tmp_ / "out").string(); });
    replace("tmp", [&] { return tmp_.string(); });
    replace("run_gap", [&] {
      copy_run(tmp_ / "run_gap");
      fs::remove(tmp_ / "run_gap" / "frames" / "frame_000002.png");
      return (tmp_ / "run_gap").string();
    });
    replace("run", [&] { return copy_run(tmp_ / "run"); });
    replace("locked_empty", [&] {
      fs::create_directories(tmp_ / "locked_empty");
      return lock(tmp_ / "locked_empty");
    });
    replace("locked", [&] {
      copy_run(tmp_ / "locked");
      return lock(tmp_ / "locked");
    });
    replace("nonempty", [&] {
      fs::create_directories(tmp_ / "nonempty");
      std::ofstream(tmp_ / "nonempty" / "notes.txt") << "someone's notes\n";
      return (tmp_ / "nonempty").string();
    });
    for (const char* f : {"fifo", "fifo_csv", "fifo_gsck"})
      replace(f, [&] {
        const std::string name = std::string(f) == "fifo"       ? "fifo.toml"
                                 : std::string(f) == "fifo_csv" ? "fifo.csv"
                                                                : "fifo.gsck";
        const fs::path p = tmp_ / name;
        if (!fs::exists(p)) ::mkfifo(p.c_str(), 0644);
        return p.string();
      });
    replace("gen_constant", [&] {
      // 10⁶ taps of one φ: refused, fast (nothing quadratic in the number of rows)
      const fs::path p = tmp_ / "constant.csv";
      if (!fs::exists(p)) {
        std::ofstream o(p);
        o << "tap,phi\n";
        for (int i = 1; i <= 1000000; ++i) o << i << ",0.8\n";
      }
      return p.string();
    });
    replace("gen_species", [&] {
      // 20 000 species: memory quadratic in the number of species
      const fs::path p = tmp_ / "species.toml";
      if (!fs::exists(p)) {
        std::ofstream o(p);
        o << "[model]\nkind = \"S\"\n[[material]]\nname = \"m\"\n";
        for (int i = 0; i < 20000; ++i)
          o << "[[species]]\nname = \"s" << i
            << "\"\nshape = \"disk\"\nradius = 0.001\ncount = 1\n";
        o << "[box]\nkind = \"periodic\"\nwidth = 10.0\n[integrator]\nkind = \"velocity_verlet\"\n"
             "dt = 1e-6\n[scene]\nduration = 0.001\n";
      }
      return p.string();
    });
    return w;
  }

  std::string copy_run(const fs::path& to) {
    fs::remove_all(to);
    fs::copy(kCorpus / "fixture_run", to, fs::copy_options::recursive);
    return to.string();
  }

  // hold DIR/.lock as a running gransim would: flock, and our PID in the file
  std::string lock(const fs::path& dir) {
    const int fd = ::open((dir / ".lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd >= 0 && ::flock(fd, LOCK_EX | LOCK_NB) == 0) {
      const std::string me = std::to_string(::getpid()) + "\n";
      if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, me.data(), me.size(), 0) < 0) {
      }
      locks_.push_back(fd);
    }
    return dir.string();
  }

  void release() {
    for (int fd : locks_) ::close(fd);
    locks_.clear();
  }

  fs::path tmp_;
  std::vector<int> locks_;
};

// AddressSanitizer's checks make the binary several times slower: the limits that separate a
// bounded case from a runaway one scale with it
#if defined(__SANITIZE_ADDRESS__)
constexpr int kSlowdown = 6;
#else
constexpr int kSlowdown = 1;
#endif

// every case of the MANIFEST: its exit code within 10 s of CPU, never a signal, never an internal
// error, the expected words in the message; a refused scene is named and leaves no output
TEST(Hostile, EveryManifestCaseEndsWithItsExitCode) {
  const fs::path tmp = scratch();
  Sandbox box(tmp);
  testing::Launch quick;
  quick.cpu_limit_s = 10 * kSlowdown;
  quick.alarm_s = 60 * kSlowdown;
  quick.env = {"OMP_NUM_THREADS=1"};
  std::map<std::string, int> per_class;
  for (const Case& c : cases()) {
    const std::vector<std::string> args = box.args(c);
    const Outcome o = run_binary(args, tmp / "log.txt", quick);
    const std::string what = c.file + " [" + c.cls + "] " + c.command;
    ++per_class[c.cls];
    ASSERT_TRUE(o.exited) << what << ": killed by signal " << o.code
                          << (o.code == SIGXCPU || o.code == SIGKILL ? " (over the CPU limit)"
                              : o.code == SIGALRM                    ? " (over the time limit)"
                                                                     : "")
                          << "\n"
                          << o.output;
    EXPECT_EQ(o.code, c.code) << what << "\n" << o.output;
    EXPECT_EQ(o.output.find("internal error"), std::string::npos) << what << "\n" << o.output;
    if (c.code == 0) continue;
    EXPECT_NE(o.output.find(c.expect), std::string::npos)
        << what << ": expected '" << c.expect << "' in\n"
        << o.output;
    EXPECT_EQ(o.output.find("completed"), std::string::npos) << what << "\n" << o.output;
    if (c.cls == "scene" && c.code == 2) {
      const fs::path out = tmp / "out";
      EXPECT_NE(o.output.find(c.file), std::string::npos) << what << ": not named\n" << o.output;
      EXPECT_TRUE(!fs::exists(out) || fs::is_empty(out)) << what << ": left output behind";
    }
  }
  for (const auto& [cls, n] : per_class)
    std::printf("hostile class %s: %d cases\n", cls.c_str(), n);
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
    const Outcome o =
        run_binary({"run", (kCorpus / f).string(), "--out", out.string(), "--force", "--quiet"},
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
      EXPECT_NE(m.find(e.expect), std::string::npos)
          << e.file << ": expected '" << e.expect << "' in " << m;
    }
  }
  EXPECT_THROW(read_checkpoint((kCorpus / "no_such.gsck").string()), InputError);
  EXPECT_THROW(read_checkpoint(kCorpus.string()), InputError);
}

}  // namespace
}  // namespace gs
