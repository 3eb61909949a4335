// JSON files in gransim's layout: rows on one line each, numbers with printf's digits, and
// older files with bare nan read back
#include "output/json_text.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace gs {
namespace {

using ojson = nlohmann::ordered_json;

// one number written as a file's row would hold it
std::string written(const ojson& v) { return json_text({{"v", v}}); }
std::string row(const std::string& text) { return "{\n  \"v\": " + text + "\n}\n"; }

TEST(JsonText, NumbersKeepThePrintfDigits) {
  EXPECT_EQ(written(json_number(12.345678, 6)), row("12.3457"));
  EXPECT_EQ(written(json_number(3.0, 6)), row("3"));
  EXPECT_EQ(written(json_number(0.0001, 6)), row("0.0001"));
  EXPECT_EQ(written(json_number(1.5e-5, 6)), row("1.5e-05"));
  EXPECT_EQ(written(json_number(-2.718281828459045, 10)), row("-2.718281828"));
  EXPECT_EQ(written(json_number(0.1 + 0.2, 10)), row("0.3"));
  EXPECT_EQ(written(json_number(1.081187006123e20, 10)), row("1.081187006e+20"));
  // nlohmann-json's own shortest form of this one has 17 digits
  EXPECT_EQ(written(json_number(0.05215849, 6)), row("0.0521585"));
  EXPECT_EQ(written(0.1), row("0.1"));
  EXPECT_TRUE(json_number(std::nan(""), 6).is_null());
  EXPECT_TRUE(json_number(-INFINITY, 10).is_null());
  EXPECT_EQ(written(std::nan("")), row("null"));
}

TEST(JsonText, RowsOnALineEachEverythingElseOnOne) {
  ojson j;
  j["name"] = "a \"quoted\" name";
  j["sets"] = ojson::array();
  j["empty"] = ojson::array();
  j["runs"] = ojson::array();
  j["runs"].push_back({{"name", "x=1"}, {"overrides", {"x=1"}}, {"wall", json_number(0.5, 6)}});
  j["runs"].push_back({{"name", "x=2"}, {"overrides", ojson::array()}, {"wall", nullptr}});
  EXPECT_EQ(json_text(j, {"runs", "empty"}),
            "{\n  \"name\": \"a \\\"quoted\\\" name\",\n  \"sets\": [],\n  \"empty\": [\n  ],\n"
            "  \"runs\": [\n    {\"name\": \"x=1\", \"overrides\": [\"x=1\"], \"wall\": 0.5},\n"
            "    {\"name\": \"x=2\", \"overrides\": [], \"wall\": null}\n  ]\n}\n");
  // a flat object is what nlohmann-json's own indented dump writes
  ojson flat;
  flat["model"] = "walk";
  flat["D"] = json_number(1.25, 10);
  EXPECT_EQ(json_text(flat), flat.dump(2) + "\n");
  // the text is JSON that reads back to the same values
  EXPECT_EQ(ojson::parse(json_text(j, {"runs"})), j);
}

TEST(JsonText, OlderFilesWithBareNonFiniteNumbersAreRead) {
  const auto j = parse_json_lenient("{\"a\": nan, \"b\": -inf, \"c\": \"nan inf\", \"d\": 2}");
  ASSERT_FALSE(j.is_discarded());
  EXPECT_TRUE(j["a"].is_null());
  EXPECT_TRUE(j["b"].is_null());
  EXPECT_EQ(j["c"], "nan inf");
  EXPECT_EQ(j["d"], 2);
  EXPECT_TRUE(parse_json_lenient("{\"a\": nonsense}").is_discarded());
  EXPECT_TRUE(parse_json_lenient("not json").is_discarded());
}

}  // namespace
}  // namespace gs
