// Curves, points and results in memory (io.hpp: parse_curves_json, open_points(PointArray),
// open_results(span)), the Python module's way in and out, held against the file readers on the
// same bytes: the .npy points are built byte by byte here, and the records taken apart here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "bezinv/io.hpp"
#include "support/expect_input_error.hpp"
#include "support/npy_bytes.hpp"
#include "support/scratch_directory.hpp"

namespace bezinv {
namespace {

constexpr double kMemoryNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kMemoryInf = std::numeric_limits<double>::infinity();

constexpr const char* kTwoCurves =
    R"({"curves": [{"id": "p", "kind": "bezier", "points": [[0, 0], [1, 2], [3, 0]]},
                   {"id": "s", "kind": "bezier", "points": [[0, 0, 0], [1, 1, 1]]}]})";

std::vector<PointRow> read_every_row(PointReader& reader) {
  std::vector<PointRow> rows, part(3);  // chunks smaller than the input
  while (const std::size_t got = reader.read(part)) rows.insert(rows.end(), part.begin(), part.begin() + got);
  return rows;
}

bool same_double(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

TEST(MemoryIo, CurvesFromTextAreTheFilesCurves) {
  test_support::ScratchDirectory dir("bezinv_memory_io_");
  const std::vector<Curve> from_file = read_curves_json(dir.write("c.json", kTwoCurves));
  const std::vector<Curve> from_text = parse_curves_json(kTwoCurves, "mine");
  ASSERT_EQ(from_text.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(from_text[i].id, from_file[i].id);
    EXPECT_EQ(from_text[i].x_num, from_file[i].x_num);
    EXPECT_EQ(from_text[i].y_den, from_file[i].y_den);
    EXPECT_EQ(from_text[i].z_num, from_file[i].z_num);
  }
  EXPECT_EQ(from_text[1].dimension(), 3);
  // Errors name the text as the file reader names the file.
  test_support::expect_input_error([] { parse_curves_json(R"({"curves": [{"id": "a", "kind": "bezier"}]})", "mine"); },
                                   {"mine", "curves[0]", "points"});
  test_support::expect_input_error([] { parse_curves_json("{\"curves\": [", "mine"); }, {"mine", "malformed"});
}

TEST(MemoryIo, ArrayRowsAreCheckedAsTheNpyReaderChecksThem) {
  const std::vector<Curve> curves = parse_curves_json(kTwoCurves);
  // Rows of three coordinates with their curve index: good, non-finite in each place, an index
  // past the end, a negative one, a plane curve's row with a z.
  const std::vector<double> xyz = {1, 1, 1,  kMemoryNan, 0, 0,  0, kMemoryInf, 0,  0, 0, kMemoryNan,
                                   0, 0, 0,  0, 0, 0,  0.5, 1, 0};
  const std::vector<std::int64_t> index = {1, 1, 1, 1, 2, -1, 0};
  test_support::ScratchDirectory dir("bezinv_memory_io_");
  std::string data, index_data;
  for (double v : xyz) test_support::append_le(data, v);
  for (std::int64_t i : index) test_support::append_le(index_data, i);
  const std::string points_path = dir.write("p.npy", test_support::npy_bytes(test_support::npy_dict("'<f8'", "(7, 3)"), data));
  const std::string index_path = dir.write("i.npy", test_support::npy_bytes(test_support::npy_dict("'<i8'", "(7,)"), index_data));
  CurveSelection selection;
  selection.index_path = index_path;
  const std::vector<PointRow> from_file = read_every_row(*open_points(points_path, curves, selection));

  PointArray array;
  array.coordinates = xyz;
  array.width = 3;
  array.curve_index = index;
  const std::vector<PointRow> from_memory = read_every_row(*open_points(array, curves));
  ASSERT_EQ(from_memory.size(), 7u);
  ASSERT_EQ(from_file.size(), 7u);
  for (std::size_t i = 0; i < 7; ++i) {
    EXPECT_EQ(from_memory[i].curve, from_file[i].curve) << i;
    EXPECT_STREQ(from_memory[i].reason, from_file[i].reason) << i;
    EXPECT_TRUE(same_double(from_memory[i].point.x, from_file[i].point.x)) << i;
    EXPECT_TRUE(same_double(from_memory[i].z, from_file[i].z)) << i;
  }
  // What the rows say, read off the format's rules rather than the file reader.
  EXPECT_EQ(from_memory[0].curve, 1);
  EXPECT_STREQ(from_memory[1].reason, "x is not finite");
  EXPECT_STREQ(from_memory[2].reason, "y is not finite");
  EXPECT_STREQ(from_memory[3].reason, "z is not finite");
  EXPECT_STREQ(from_memory[4].reason, "curve index past the end");
  EXPECT_STREQ(from_memory[5].reason, "negative curve index");
  EXPECT_STREQ(from_memory[6].reason, "z given for a point of a plane curve");
}

TEST(MemoryIo, WholeArrayMistakesAreInputErrorsNamingThem) {
  const std::vector<Curve> curves = parse_curves_json(kTwoCurves);
  const std::vector<double> six(6, 0.0);
  const std::vector<std::int64_t> two_indices = {0, 0};
  const auto open = [&](std::size_t width, std::string curve, std::span<const std::int64_t> index) {
    PointArray array;
    array.coordinates = six;
    array.width = width;
    array.curve = std::move(curve);
    array.curve_index = index;
    array.name = "pts";
    return open_points(array, curves);
  };
  test_support::expect_input_error([&] { open(4, "p", {}); }, {"pts", "4 coordinates a row"});
  test_support::expect_input_error([&] { open(2, "zz", {}); }, {"pts", "curve 'zz'"});
  test_support::expect_input_error([&] { open(3, "p", {}); }, {"pts", "(2, 3)", "plane curve"});
  test_support::expect_input_error([&] { open(2, "s", {}); }, {"pts", "(3, 2)", "space curve"});
  test_support::expect_input_error([&] { open(2, "", {}); }, {"pts", "name the curve"});
  test_support::expect_input_error([&] { open(2, "p", two_indices); }, {"pts", "not both"});
  test_support::expect_input_error([&] { open(2, "", two_indices); }, {"pts", "2 indices for 3 points"});
  PointArray odd;
  odd.coordinates = std::span(six).first(5);
  odd.curve = "p";
  test_support::expect_input_error([&] { open_points(odd, curves); }, {"5 numbers"});
}

TEST(MemoryIo, ResultRecordsAreOutNpysRecords) {
  PointResult a;
  a.t = 0.25;
  a.residual = 1e-17;
  a.sigma_min = 3e-18;
  a.status = Status::ok;
  a.path = Path::bezout_lu;
  PointResult b;
  b.status = Status::invalid_input;
  b.reason = "x is not finite";
  std::vector<char> records(2 * kResultRecordBytes);
  std::vector<const char*> reasons(2);
  const auto writer = open_results(std::span(records), std::span(reasons));
  writer->write(std::vector<PointResult>{a, b});
  writer->commit();
  // Taken apart by the layout of result_descr(): five little-endian doubles, then two bytes.
  EXPECT_EQ(result_descr(),
            "[('t', '<f8'), ('residual', '<f8'), ('t2', '<f8'), ('sigma_min', '<f8'), ('sigma_next', '<f8'), "
            "('status', '|u1'), ('path', '|u1')]");
  double t = 0, residual = 0, t2 = 0;
  std::memcpy(&t, records.data(), 8);
  std::memcpy(&residual, records.data() + 8, 8);
  std::memcpy(&t2, records.data() + 16, 8);
  EXPECT_EQ(t, 0.25);
  EXPECT_EQ(residual, 1e-17);
  EXPECT_TRUE(std::isnan(t2));
  EXPECT_EQ(records[40], static_cast<char>(Status::ok));
  EXPECT_EQ(records[41], static_cast<char>(Path::bezout_lu));
  EXPECT_EQ(records[kResultRecordBytes + 40], static_cast<char>(Status::invalid_input));
  EXPECT_STREQ(reasons[0], "");
  EXPECT_STREQ(reasons[1], "x is not finite");
  // A row more than the memory holds is refused, not written past its end.
  test_support::expect_input_error([&] { writer->write(std::vector<PointResult>{a}); }, {"more rows than the 2"});
}

}  // namespace
}  // namespace bezinv
