// the [rfm] scene section (docs/scene-format.md): defaults follow the drive, every key is read,
// written back by scene_to_toml and parsed to the same keys, and bad values name file:line:key
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "scene/parse.hpp"

namespace gs {
namespace {

constexpr const char* kBase = R"(
[model]
kind = "S"
[[species]]
name = "bead"
radius = 0.0015
count = 100
[box]
kind = "periodic"
width = 0.1
[drive]
kind = "random_force"
)";

TEST(RfmScene, DefaultsFollowTheDrive) {
  const SceneSpec s = parse_scene_string(kBase, "a.toml");
  EXPECT_TRUE(s.rfm.enabled);  // on for the random force
  EXPECT_FALSE(s.rfm.given);
  EXPECT_EQ(s.rfm.sample_every, 1000);
  EXPECT_EQ(s.rfm.discard_time, 1.0);
  EXPECT_EQ(s.resolved.at("rfm.sample_every"), "1000");
  // another drive: off, and no [rfm] keys unless the section is given
  const SceneSpec n = parse_scene_string(kBase, "a.toml", {"drive.kind=none"});
  EXPECT_FALSE(n.rfm.enabled);
  EXPECT_EQ(n.resolved.count("rfm.enabled"), 0u);
  const SceneSpec g =
      parse_scene_string(std::string(kBase) + "[rfm]\n", "a.toml", {"drive.kind=none"});
  EXPECT_TRUE(g.rfm.enabled);  // a freely cooling gas that asks for the measurements
}

TEST(RfmScene, KeysRoundTrip) {
  const std::string text = std::string(kBase) + R"(
[rfm]
sample_every = 250
discard_time = 0.5
blocks = 8
v_max = 3
v_bins = 300
structure_every = 4
sk_nmax = 40
gr_bins = 50
gr_rmax = 0.02
path_bins = 60
path_min = 1e-7
path_max = 0.1
gap_bins = 100
gap_min = 1e-10
)";
  const SceneSpec s = parse_scene_string(text, "a.toml");
  EXPECT_EQ(s.rfm.sample_every, 250);
  EXPECT_EQ(s.rfm.discard_time, 0.5);
  EXPECT_EQ(s.rfm.blocks, 8);
  EXPECT_EQ(s.rfm.v_max, 3.0);
  EXPECT_EQ(s.rfm.structure_every, 4);
  EXPECT_EQ(s.rfm.sk_nmax, 40);
  EXPECT_EQ(s.rfm.gr_rmax, 0.02);
  EXPECT_EQ(s.rfm.path_min, 1e-7);
  EXPECT_EQ(s.rfm.gap_min, 1e-10);
  const SceneSpec back = parse_scene_string(scene_to_toml(s), "back.toml");
  EXPECT_EQ(back.resolved, s.resolved);
  EXPECT_EQ(back.rfm.gap_bins, 100);
}

TEST(RfmScene, BadValuesNameTheKey) {
  auto error_of = [](const std::string& extra) {
    try {
      parse_scene_string(std::string(kBase) + "[rfm]\n" + extra, "bad.toml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(
      error_of("gr_rmax = 0.08\n").find("bad.toml:14: key 'rfm.gr_rmax': must be at most half"),
      std::string::npos)
      << error_of("gr_rmax = 0.08\n");
  EXPECT_NE(error_of("sample_every = 0\n").find("key 'rfm.sample_every'"), std::string::npos);
  EXPECT_NE(error_of("path_min = 1e-3\npath_max = 1e-4\n").find("key 'rfm.path_max'"),
            std::string::npos);
  EXPECT_NE(error_of("sampel_every = 10\n").find("did you mean 'sample_every'"), std::string::npos);
}

}  // namespace
}  // namespace gs
