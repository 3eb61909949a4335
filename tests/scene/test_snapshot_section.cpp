// [output.snapshots]: values, defaults, the written form (only when given) and errors naming
// file, line and key
#include <gtest/gtest.h>

#include "scene/parse.hpp"
#include "scene_test_util.hpp"

namespace gs {
namespace {

using test::edit;
using test::error_of;
using test::line_of;

const std::string kBase = R"(
[[species]]
name = "g"
radius = 0.009
count = 10

[box]
width = 0.2

[drive]
kind = "negative_g"
taps = 3
)";

const std::string kSnap = R"(
[output.snapshots]
every_time = 0.25
times = [0.1, 0.7, 2]
at_taps = true
formats = ["xyz"]
vtp_encoding = "ascii"
contacts = false
)";

TEST(SceneSnapshots, EveryKeyIsRead) {
  const SnapshotSpec o = parse_scene_string(kBase + kSnap, "s.toml").output.snapshots;
  EXPECT_TRUE(o.given);
  EXPECT_TRUE(o.enabled());
  EXPECT_EQ(o.every_time, 0.25);
  EXPECT_EQ(o.times, (std::vector<double>{0.1, 0.7, 2.0}));
  EXPECT_TRUE(o.at_taps);
  EXPECT_FALSE(o.vtp);
  EXPECT_TRUE(o.xyz);
  EXPECT_FALSE(o.vtp_binary);
  EXPECT_FALSE(o.contacts);
}

TEST(SceneSnapshots, DefaultsAndTheWrittenForm) {
  // no table: off, and the written scene has no [output.snapshots] (other scenes unchanged)
  const SceneSpec none = parse_scene_string(kBase, "d.toml");
  EXPECT_FALSE(none.output.snapshots.given);
  EXPECT_FALSE(none.output.snapshots.enabled());
  EXPECT_EQ(scene_to_toml(none).find("snapshots"), std::string::npos);
  EXPECT_EQ(none.resolved.count("output.snapshots.at_taps"), 0u);
  // a table with only at_taps: both formats and the contacts
  const SceneSpec d = parse_scene_string(kBase + "[output.snapshots]\nat_taps = true\n", "d.toml");
  EXPECT_TRUE(d.output.snapshots.vtp && d.output.snapshots.xyz && d.output.snapshots.contacts);
  EXPECT_TRUE(d.output.snapshots.vtp_binary);
  EXPECT_EQ(d.resolved.at("output.snapshots.formats"), "[\"vtp\", \"xyz\"]");
  EXPECT_EQ(d.resolved.at("output.snapshots.vtp_encoding"), "\"binary\"");
  // written back, read again: the same
  const SceneSpec s = parse_scene_string(kBase + kSnap, "s.toml");
  const SnapshotSpec back = parse_scene_string(scene_to_toml(s), "rt.toml").output.snapshots;
  EXPECT_EQ(back.every_time, 0.25);
  EXPECT_EQ(back.times, s.output.snapshots.times);
  EXPECT_TRUE(back.at_taps && back.xyz && back.given);
  EXPECT_FALSE(back.vtp || back.contacts || back.vtp_binary);
  // and from the command line
  const SceneSpec o = parse_scene_string(kBase, "o.toml", {"output.snapshots.every_time=0.5"});
  EXPECT_EQ(o.output.snapshots.every_time, 0.5);
  EXPECT_TRUE(o.output.snapshots.enabled());
}

TEST(SceneSnapshots, ErrorsNameLineAndKey) {
  const std::string text = kBase + kSnap;
  const std::string order = edit(text, "[0.1, 0.7, 2]", "[0.1, 0.05, 2]");
  const std::string m = error_of(order);
  EXPECT_NE(m.find("t.toml:" + std::to_string(line_of(order, "times"))), std::string::npos) << m;
  EXPECT_NE(m.find("key 'output.snapshots.times'"), std::string::npos) << m;
  EXPECT_NE(m.find("strictly ascending"), std::string::npos) << m;
  EXPECT_NE(error_of(edit(text, "[0.1, 0.7, 2]", "[-1]")).find(">= 0"), std::string::npos);
  EXPECT_NE(error_of(edit(text, "[0.1, 0.7, 2]", "[0.1, \"x\"]")).find("element 1 is string"),
            std::string::npos);
  EXPECT_NE(error_of(edit(text, "[0.1, 0.7, 2]", "0.1")).find("expected an array"),
            std::string::npos);
  EXPECT_NE(error_of(edit(text, "every_time = 0.25", "every_time = -1")).find(">= 0"),
            std::string::npos);
  const std::string f = error_of(edit(text, "[\"xyz\"]", "[\"vtk\"]"));
  EXPECT_NE(f.find("key 'output.snapshots.formats'"), std::string::npos) << f;
  EXPECT_NE(f.find("did you mean 'vtp'"), std::string::npos) << f;
  EXPECT_NE(error_of(edit(text, "[\"xyz\"]", "[\"xyz\", \"xyz\"]")).find("twice"),
            std::string::npos);
  EXPECT_NE(error_of(edit(text, "[\"xyz\"]", "[]")).find("writes nothing"), std::string::npos);
  const std::string e = error_of(edit(text, "\"ascii\"", "\"binry\""));
  EXPECT_NE(e.find("key 'output.snapshots.vtp_encoding'"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'binary'"), std::string::npos) << e;
  EXPECT_NE(
      error_of(edit(text, "contacts = false", "contact = false")).find("did you mean 'contacts'"),
      std::string::npos);
  // at the taps of a drive that has none
  const std::string g = error_of(edit(edit(text, "\"negative_g\"", "\"none\""), "taps = 3", ""));
  EXPECT_NE(g.find("t.toml:" + std::to_string(line_of(text, "at_taps"))), std::string::npos) << g;
  EXPECT_NE(g.find("needs a tapping drive"), std::string::npos) << g;
  // the table itself must be a table
  EXPECT_NE(error_of(kBase + "[output]\nsnapshots = 3\n").find("expected a table"),
            std::string::npos);
}

}  // namespace
}  // namespace gs
