// Output writers and probes (io/probe_recorder.hpp): probes.csv at full precision.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "ancf/io/probe_recorder.hpp"

namespace ancf {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string cell; std::getline(s, cell, ',');) out.push_back(cell);
  return out;
}

// Every value written to probes.csv reads back (strtod) to the same bits: values that need all
// 17 significant digits, the extremes of the double range, subnormals, signed zero; and short
// values stay short (0.05, not 0.050000000000000003).
TEST(CsvWriter, ValuesRoundTripBitExactly) {
  const std::vector<double> values = {0.05,
                                      1.0 / 3.0,
                                      std::numbers::pi * 1e-300,
                                      0.1 + 0.2,
                                      -2.0 / 3.0 * 1e17,
                                      std::numeric_limits<double>::max(),
                                      std::numeric_limits<double>::min(),
                                      std::numeric_limits<double>::denorm_min(),
                                      -0.0,
                                      1.0 + std::numeric_limits<double>::epsilon(),
                                      123456789.01234567};
  const fs::path file = fs::temp_directory_path() / "ancf_csv_round_trip.csv";
  std::vector<std::string> names(values.size(), "v");
  {
    CsvWriter csv(file.string(), names);
    csv.write(values);
    EXPECT_EQ(csv.rows(), 1);
  }
  std::ifstream in(file);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  const std::vector<std::string> cells = split(row);
  ASSERT_EQ(cells.size(), values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double back = std::strtod(cells[i].c_str(), nullptr);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(back), std::bit_cast<std::uint64_t>(values[i]))
        << cells[i];
    EXPECT_LE(cells[i].size(), 24u) << cells[i];  // sign, 17 digits, point, exponent
  }
  EXPECT_EQ(cells[0], "0.05");
  EXPECT_EQ(cells[1], "0.3333333333333333");
}

}  // namespace
}  // namespace ancf
