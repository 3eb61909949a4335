// the [render] section: values, defaults that follow the drive, the written form, and errors
#include <gtest/gtest.h>

#include "scene/parse.hpp"
#include "scene/render_section.hpp"
#include "scene_test_util.hpp"

namespace gs {
namespace {

using test::edit;
using test::error_of;
using test::line_of;

// a small scene: one species in a walled box
const std::string kBase = R"(
[[species]]
name = "g"
radius = 0.009
count = 10

[box]
width = 0.2
)";

// every [render] key set to a non-default value
const std::string kRender = R"(
[drive]
kind = "rotating_g"

[render]
enabled = true
frames = true
movie = false
schedule = "rest"
every = 7
fps = 12
slowmo = 0.25
start = 1.5
size = [640, 482]
msaa = 2
camera = [0.0, 0.01, 0.2, 0.3]
margin = 0.1
color_by = "pressure"
colormap = "magma"
range = [0, 2.5]
colorbar = false
force_chains = true
gravity_arrow = false
test_rect = false
clock = false
title = "rotating \"g\""
crf = 30
preset = "veryfast"
renderer = "software"
trajectory_every = 50
trajectory_formats = ["h5md"]
)";

void expect_same_render(const RenderSpec& a, const RenderSpec& b) {
  EXPECT_EQ(a.enabled, b.enabled);
  EXPECT_EQ(a.frames, b.frames);
  EXPECT_EQ(a.movie, b.movie);
  EXPECT_EQ(a.schedule, b.schedule);
  EXPECT_EQ(a.every, b.every);
  EXPECT_EQ(a.fps, b.fps);
  EXPECT_EQ(a.slowmo, b.slowmo);
  EXPECT_EQ(a.start, b.start);
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.msaa, b.msaa);
  EXPECT_EQ(a.region, b.region);
  EXPECT_EQ(a.margin, b.margin);
  EXPECT_EQ(a.color_by, b.color_by);
  EXPECT_EQ(a.colormap, b.colormap);
  EXPECT_EQ(a.range, b.range);
  EXPECT_EQ(a.colorbar, b.colorbar);
  EXPECT_EQ(a.force_chains, b.force_chains);
  EXPECT_EQ(a.gravity_arrow, b.gravity_arrow);
  EXPECT_EQ(a.test_rect, b.test_rect);
  EXPECT_EQ(a.clock, b.clock);
  EXPECT_EQ(a.title, b.title);
  EXPECT_EQ(a.crf, b.crf);
  EXPECT_EQ(a.preset, b.preset);
  EXPECT_EQ(a.renderer, b.renderer);
  EXPECT_EQ(a.trajectory_every, b.trajectory_every);
  EXPECT_EQ(a.trajectory_xyz, b.trajectory_xyz);
  EXPECT_EQ(a.trajectory_h5md, b.trajectory_h5md);
}

TEST(SceneRender, EveryKeyIsRead) {
  const RenderSpec r = parse_scene_string(kBase + kRender, "r.toml").render;
  EXPECT_TRUE(r.enabled);
  EXPECT_TRUE(r.frames);
  EXPECT_FALSE(r.movie);
  EXPECT_EQ(r.schedule, RenderSchedule::Rest);
  EXPECT_EQ(r.every, 7);
  EXPECT_EQ(r.fps, 12);
  EXPECT_EQ(r.slowmo, 0.25);
  EXPECT_EQ(r.start, 1.5);
  EXPECT_EQ(r.width, 640);
  EXPECT_EQ(r.height, 482);
  EXPECT_EQ(r.msaa, 2);
  ASSERT_TRUE(r.region);
  EXPECT_EQ((*r.region)[1], 0.01);
  EXPECT_EQ((*r.region)[3], 0.3);
  EXPECT_EQ(r.margin, 0.1);
  EXPECT_EQ(r.color_by, "pressure");
  EXPECT_EQ(r.colormap, "magma");
  ASSERT_TRUE(r.range);
  EXPECT_EQ((*r.range)[0], 0.0);
  EXPECT_EQ((*r.range)[1], 2.5);
  EXPECT_FALSE(r.colorbar);
  EXPECT_TRUE(r.force_chains);
  EXPECT_FALSE(r.gravity_arrow);
  EXPECT_FALSE(r.test_rect);
  EXPECT_FALSE(r.clock);
  EXPECT_EQ(r.title, "rotating \"g\"");
  EXPECT_EQ(r.crf, 30);
  EXPECT_EQ(r.preset, "veryfast");
  EXPECT_EQ(r.renderer, "software");
  EXPECT_EQ(r.trajectory_every, 50);
  EXPECT_FALSE(r.trajectory_xyz);
  EXPECT_TRUE(r.trajectory_h5md);
}

TEST(SceneRender, RoundTripThroughTheWrittenScene) {
  const SceneSpec s = parse_scene_string(kBase + kRender, "r.toml");
  const SceneSpec back = parse_scene_string(scene_to_toml(s), "rt.toml");
  expect_same_render(s.render, back.render);
  EXPECT_EQ(s.resolved.at("render.camera"), "[0.0, 0.01, 0.2, 0.3]");
  EXPECT_EQ(s.resolved.at("render.size"), "[640, 482]");
  EXPECT_EQ(s.resolved.at("render.schedule"), "\"rest\"");
  // and the defaults round-trip too (no section: disabled, "fit", "auto")
  const SceneSpec d = parse_scene_string(kBase, "d.toml");
  EXPECT_EQ(d.resolved.at("render.enabled"), "false");
  EXPECT_EQ(d.resolved.at("render.camera"), "\"fit\"");
  EXPECT_EQ(d.resolved.at("render.range"), "\"auto\"");
  EXPECT_EQ(d.resolved.at("render.trajectory_formats"), "[\"xyz\"]");
  expect_same_render(d.render, parse_scene_string(scene_to_toml(d), "rt.toml").render);
}

TEST(SceneRender, Defaults) {
  // no section: nothing recorded
  const RenderSpec none = parse_scene_string(kBase, "d.toml").render;
  EXPECT_FALSE(none.enabled);
  EXPECT_EQ(none.trajectory_every, 0);
  EXPECT_TRUE(none.trajectory_xyz);
  EXPECT_FALSE(none.trajectory_h5md);
  // an empty section records nothing either (a --set render.* creates one)
  EXPECT_FALSE(parse_scene_string(kBase + "[render]\n", "d.toml").render.enabled);
  // enabled: a 720p movie at 30 fps in real time, coloured by speed
  const RenderSpec r = parse_scene_string(kBase + "[render]\nenabled = true\n", "d.toml").render;
  EXPECT_TRUE(r.enabled);
  EXPECT_TRUE(r.movie);
  EXPECT_FALSE(r.frames);
  EXPECT_EQ(r.schedule, RenderSchedule::Time);
  EXPECT_EQ(r.fps, 30);
  EXPECT_EQ(r.slowmo, 1.0);
  EXPECT_EQ(r.width, 1280);
  EXPECT_EQ(r.height, 720);
  EXPECT_EQ(r.color_by, "speed");
  EXPECT_EQ(r.colormap, "viridis");
  EXPECT_FALSE(r.region);
  EXPECT_FALSE(r.range);
  // constant gravity: no arrow, no test rectangle; tapping drives: both
  EXPECT_FALSE(r.gravity_arrow);
  EXPECT_FALSE(r.test_rect);
  const RenderSpec tap =
      parse_scene_string(kBase + "[drive]\nkind = \"negative_g\"\n[render]\n", "d.toml").render;
  EXPECT_TRUE(tap.gravity_arrow);
  EXPECT_TRUE(tap.test_rect);
  // overrides reach the section
  const RenderSpec o =
      parse_scene_string(kBase, "d.toml", {"render.enabled=true", "render.size=[320, 240]"}).render;
  EXPECT_TRUE(o.enabled);
  EXPECT_EQ(o.width, 320);
}

TEST(SceneRender, ErrorsNameLineAndKey) {
  const std::string text = kBase + kRender;
  // a colour the renderer does not know, with a suggestion
  const std::string bad = edit(text, "\"pressure\"", "\"presure\"");
  const std::string m = error_of(bad);
  EXPECT_NE(m.find("t.toml:" + std::to_string(line_of(bad, "color_by"))), std::string::npos) << m;
  EXPECT_NE(m.find("key 'render.color_by'"), std::string::npos) << m;
  EXPECT_NE(m.find("did you mean 'pressure'"), std::string::npos) << m;
  // size, camera, range, schedule, fps, colormap, preset, renderer
  EXPECT_NE(error_of(edit(text, "[640, 482]", "[640]")).find("expected [width, height]"),
            std::string::npos);
  EXPECT_NE(error_of(edit(text, "[640, 482]", "[640, 4]")).find("16…8192"), std::string::npos);
  EXPECT_NE(error_of(edit(text, "[640, 482]", "[640.5, 482]")).find("integer"), std::string::npos);
  EXPECT_NE(error_of(edit(text, "[0.0, 0.01, 0.2, 0.3]", "\"box\"")).find("expected \"fit\""),
            std::string::npos);
  EXPECT_NE(error_of(edit(text, "[0.0, 0.01, 0.2, 0.3]", "[0.2, 0, 0.1, 1]")).find("x1 > x0"),
            std::string::npos);
  EXPECT_NE(error_of(edit(text, "[0, 2.5]", "[3, 2.5]")).find("lo < hi"), std::string::npos);
  EXPECT_NE(error_of(edit(text, "[0, 2.5]", "[0, nan]")).find("finite"), std::string::npos);
  EXPECT_NE(error_of(edit(text, "fps = 12", "fps = 0")).find("render.fps"), std::string::npos);
  EXPECT_NE(error_of(edit(text, "\"magma\"", "\"rainbow\"")).find("\"viridis\""),
            std::string::npos);
  EXPECT_NE(error_of(edit(text, "\"veryfast\"", "\"fastest\"")).find("render.preset"),
            std::string::npos);
  EXPECT_NE(error_of(edit(text, "\"software\"", "\"vulkan\"")).find("\"gl\""), std::string::npos);
  EXPECT_NE(error_of(edit(text, "slowmo = 0.25", "slowmo = 0")).find("must be > 0"),
            std::string::npos);
  const std::string tf = error_of(edit(text, "[\"h5md\"]", "[\"h5\"]"));
  EXPECT_NE(tf.find("key 'render.trajectory_formats'"), std::string::npos) << tf;
  EXPECT_NE(tf.find("did you mean 'h5md'"), std::string::npos) << tf;
  EXPECT_NE(error_of(edit(text, "[\"h5md\"]", "[]")).find("is empty"), std::string::npos);
  EXPECT_NE(error_of(edit(text, "[\"h5md\"]", "[\"xyz\", \"xyz\"]")).find("twice"),
            std::string::npos);
  EXPECT_NE(error_of(edit(text, "trajectory_every = 50", "trajectory_evry = 50"))
                .find("did you mean 'trajectory_every'"),
            std::string::npos);
  // nothing to write
  EXPECT_NE(error_of(edit(text, "frames = true", "frames = false")).find("at least one of"),
            std::string::npos);
  // per-tap schedules need a tapping drive
  const std::string g = error_of(edit(text, "\"rotating_g\"", "\"gravity\""));
  EXPECT_NE(g.find("key 'render.schedule'"), std::string::npos) << g;
  EXPECT_NE(g.find("tapping drive"), std::string::npos) << g;
}

}  // namespace
}  // namespace gs
