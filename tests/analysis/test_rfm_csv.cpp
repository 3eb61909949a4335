// the RFM tables as the one CSV writer of output/ writes them and analysis/ reads them back:
// every number reads back bit for bit, counts in the metadata sidecar are JSON integers, a
// non-finite value is null, and a bad file is named with its line
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "analysis/rfm_csv.hpp"
#include "core/error.hpp"
#include "core/records.hpp"
#include "output/csv.hpp"

namespace gs::rfm {
namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(RfmCsv, CountsInTheSidecarAreIntegers) {
  const auto dir = std::filesystem::temp_directory_path() / "gs_rfm_csv_meta";
  std::filesystem::create_directories(dir);
  const auto path = dir / "hist.csv";
  {
    const auto w = csv_records().create(path.string(), {"x", "count"},
                                        {{"n", 400.0},
                                         {"total", 139982.0},
                                         {"lo", 0.25},
                                         {"big", 1e300},
                                         {"gap", std::numeric_limits<double>::quiet_NaN()}});
    w->row({1.0, 2.0});
  }
  const std::string side = slurp(table_meta_path(path));
  EXPECT_NE(side.find("\"n\": 400,"), std::string::npos) << side;
  EXPECT_NE(side.find("\"total\": 139982,"), std::string::npos) << side;
  EXPECT_NE(side.find("\"lo\": 0.25,"), std::string::npos) << side;
  EXPECT_EQ(side.find("400.0"), std::string::npos) << side;
  EXPECT_NE(side.find("\"gap\": null"), std::string::npos) << side;
  const CsvTable t = read_csv(path);
  EXPECT_EQ(t.meta.at("n"), 400.0);
  EXPECT_EQ(t.meta.at("big"), 1e300);
  EXPECT_TRUE(std::isnan(t.meta.at("gap")));
  std::filesystem::remove_all(dir);
}

TEST(RfmCsv, RoundTripIsExact) {
  // 17 significant digits in the table, every digit in the sidecar: read back bit for bit
  const auto path = std::filesystem::temp_directory_path() / "gs_rfm_csv_roundtrip.csv";
  {
    const auto w =
        csv_records().create(path.string(), {"k", "S"}, {{"D_f", 1.6077}, {"k_D", 1.0 / 3.0}});
    w->row({0.1, 1e-300});
    w->row({2.0 / 3.0, -5.5e12});
    EXPECT_THROW(w->row({1.0}), std::logic_error);  // a row shorter than the header
  }
  const CsvTable t = read_csv(path);
  EXPECT_EQ(t.meta.at("D_f"), 1.6077);
  EXPECT_EQ(t.meta.at("k_D"), 1.0 / 3.0);
  ASSERT_EQ(t.column.at("k").size(), 2u);
  EXPECT_EQ(t.column.at("k")[0], 0.1);
  EXPECT_EQ(t.column.at("k")[1], 2.0 / 3.0);
  EXPECT_EQ(t.column.at("S")[0], 1e-300);
  EXPECT_EQ(t.column.at("S")[1], -5.5e12);
  std::filesystem::remove(path);
  std::filesystem::remove(table_meta_path(path));
}

TEST(RfmCsv, BadInputNamesFileAndLine) {
  const auto path = std::filesystem::temp_directory_path() / "gs_rfm_csv_bad.csv";
  {
    std::ofstream o(path);
    o << "# a=1\nx,y\n1,2\n3,oops\n";
  }
  try {
    read_csv(path);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(":4"), std::string::npos) << e.what();
    EXPECT_EQ(e.key(), "y");
  }
  std::filesystem::remove(path);
  EXPECT_THROW(read_csv(path), InputError);
}

}  // namespace
}  // namespace gs::rfm
