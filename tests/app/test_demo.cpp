// the first command a user runs shows what the program is for: the demo scene writes a movie
// of the fall and a picture of the settled pile, and its last line names them
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;

TEST(Demo, WritesAPictureAndAMovieAndNamesThem) {
  const fs::path tmp = fs::temp_directory_path() / ("gs-demo-" + std::to_string(::getpid()));
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  testing::Launch how;
  how.alarm_s = 120;
  const fs::path out = tmp / "demo";
  const auto r = testing::run_binary({"run", std::string(GS_SOURCE_DIR) + "/scenes/demo.toml",
                                      "--out", out.string(), "--set", "scene.duration=0.3"},
                                     tmp / "log.txt", how);
  ASSERT_EQ(r.code, 0) << r.output;
  // a PNG (its signature) of the right size class, and a non-trivial MP4
  std::ifstream png(out / "final.png", std::ios::binary);
  char sig[8] = {};
  png.read(sig, 8);
  EXPECT_EQ(std::string(sig + 1, 3), "PNG");
  EXPECT_GT(fs::file_size(out / "final.png"), 5000u);
  EXPECT_GT(fs::file_size(out / "movie.mp4"), 5000u);
  // the last line names both
  const std::string last = r.output.substr(r.output.find_last_of('\r') + 1);
  EXPECT_NE(last.find((out / "final.png").string()), std::string::npos) << last;
  EXPECT_NE(last.find((out / "movie.mp4").string()), std::string::npos) << last;
  fs::remove_all(tmp);
}

}  // namespace
}  // namespace gs
