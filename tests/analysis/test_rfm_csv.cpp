// the metadata sidecar of the RFM tables: counts are JSON integers, other numbers keep every
// digit, a non-finite value is null, and the reader gets back what was written
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "analysis/rfm_csv.hpp"

namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(RfmCsv, CountsInTheSidecarAreIntegers) {
  const auto dir = std::filesystem::temp_directory_path() / "gs_rfm_csv_meta";
  std::filesystem::create_directories(dir);
  const auto path = dir / "hist.csv";
  {
    gs::rfm::CsvWriter w(path, {"x", "count"},
                         {{"n", 400.0},
                          {"total", 139982.0},
                          {"lo", 0.25},
                          {"big", 1e300},
                          {"gap", std::numeric_limits<double>::quiet_NaN()}});
    w.row({1.0, 2.0});
  }
  const std::string side = slurp(gs::rfm::meta_path(path));
  EXPECT_NE(side.find("\"n\": 400,"), std::string::npos) << side;
  EXPECT_NE(side.find("\"total\": 139982,"), std::string::npos) << side;
  EXPECT_NE(side.find("\"lo\": 0.25,"), std::string::npos) << side;
  EXPECT_EQ(side.find("400.0"), std::string::npos) << side;
  EXPECT_NE(side.find("\"gap\": null"), std::string::npos) << side;
  const gs::rfm::CsvTable t = gs::rfm::read_csv(path);
  EXPECT_EQ(t.meta.at("n"), 400.0);
  EXPECT_EQ(t.meta.at("big"), 1e300);
  EXPECT_TRUE(std::isnan(t.meta.at("gap")) || t.meta.count("gap") == 1);
  std::filesystem::remove_all(dir);
}
