// The file formats (io.hpp): CURVES.json and POINTS.csv readers, the OUT.csv writer.
// Expected numbers are the C++ compiler's reading of the same decimal literals written into the
// files (an independent parser), and every error test names the file and the line or field the
// message must point at.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "support/bits.hpp"
#include "bezinv/io.hpp"
#include "io/curves_text.hpp"
#include "io/read_points_csv.hpp"
#include "support/expect_input_error.hpp"
#include "support/scratch_directory.hpp"
#include "support/split.hpp"

namespace bezinv {
namespace {

using test_support::same_bits;

namespace fs = std::filesystem;

using test_support::read_file;
using test_support::ScratchDirectory;
using test_support::split;

using test_support::expect_input_error;

// ---------------------------------------------------------------------------------------------
// CURVES.json

class IoCurvesJson : public ::testing::Test {
 protected:
  ScratchDirectory scratch{"bezinv-io-test-"};

  // Writes curves.json and expects read_curves_json to refuse it with these fragments (the file
  // name always among them).
  void expect_refused(std::string_view json, std::initializer_list<std::string> fragments) {
    const std::string path = scratch.write("curves.json", json);
    expect_input_error([&] { read_curves_json(path); }, fragments);
    expect_input_error([&] { read_curves_json(path); }, {path});
  }
};

TEST_F(IoCurvesJson, ReadsTheThreeKindsWithExactNumbers) {
  const std::string path = scratch.write("curves.json", R"({"curves": [
    {"id": "cubic", "kind": "bezier", "points": [[0, 0], [0.1, 2.5e-3], [3, -1.5], [123456789012345678, 1e-300]]},
    {"id": "arc", "kind": "rational_bezier", "points": [[1, 0], [1, 1], [0, 1]], "weights": [1, 0.7071067811865476, 1]},
    {"id": "sep", "kind": "rational", "x_num": [0, 1, 2], "x_den": [1, 2, 1], "y_num": [1, -0.3, 0.2], "y_den": [2, 3, 4]}
  ]})");
  const std::vector<Curve> curves = read_curves_json(path);
  ASSERT_EQ(curves.size(), 3u);

  EXPECT_EQ(curves[0].id, "cubic");
  EXPECT_EQ(curves[0].kind, CurveKind::bezier);
  // 123456789012345678 > 2^53: JSON holds it as an integer, the double must be its rounding,
  // exactly as the compiler rounds the same literal.
  EXPECT_EQ(curves[0].x_num, (std::vector<double>{0, 0.1, 3, 123456789012345678.0}));
  EXPECT_EQ(curves[0].y_num, (std::vector<double>{0, 2.5e-3, -1.5, 1e-300}));
  EXPECT_EQ(curves[0].x_den, (std::vector<double>{1, 1, 1, 1}));
  EXPECT_EQ(curves[0].y_den, (std::vector<double>{1, 1, 1, 1}));

  EXPECT_EQ(curves[1].id, "arc");
  EXPECT_EQ(curves[1].kind, CurveKind::rational_bezier);
  const double w = 0.7071067811865476;
  EXPECT_EQ(curves[1].x_den, (std::vector<double>{1, w, 1}));
  EXPECT_EQ(curves[1].y_den, (std::vector<double>{1, w, 1}));
  EXPECT_EQ(curves[1].x_num, (std::vector<double>{1, w, 0}));  // w_i x_i
  EXPECT_EQ(curves[1].y_num, (std::vector<double>{0, w, 1}));

  EXPECT_EQ(curves[2].id, "sep");
  EXPECT_EQ(curves[2].kind, CurveKind::rational);
  EXPECT_EQ(curves[2].x_num, (std::vector<double>{0, 1, 2}));
  EXPECT_EQ(curves[2].x_den, (std::vector<double>{1, 2, 1}));
  EXPECT_EQ(curves[2].y_num, (std::vector<double>{1, -0.3, 0.2}));
  EXPECT_EQ(curves[2].y_den, (std::vector<double>{2, 3, 4}));
}

TEST_F(IoCurvesJson, TextInMemoryReadsAsTheFileAndNamesTheGivenPath) {
  // parse_curves_json is read_curves_json after the file is read (the fuzz target's entry).
  const std::string json = R"({"curves": [
    {"id": "a", "kind": "bezier", "points": [[0, 0], [1, 2], [3, 1]]},
    {"id": "m", "kind": "matrix_weighted_bezier", "points": [[0, 0], [1, 1]], "matrices": [[[1, 0], [0, 2]], [[2, 0.5], [0.5, 1]]]}
  ]})";
  const std::string path = scratch.write("curves.json", json);
  const std::vector<Curve> from_file = read_curves_json(path), from_text = parse_curves_json(json, "named.json");
  ASSERT_EQ(from_text.size(), from_file.size());
  for (std::size_t i = 0; i < from_file.size(); ++i) {
    EXPECT_EQ(from_text[i].id, from_file[i].id);
    EXPECT_EQ(from_text[i].x_num, from_file[i].x_num);
    EXPECT_EQ(from_text[i].y_den, from_file[i].y_den);
  }
  const auto matrix_weighted = detail::parse_matrix_weighted_json(json, "named.json");
  ASSERT_EQ(matrix_weighted.size(), 2u);
  EXPECT_FALSE(matrix_weighted[0].has_value());
  EXPECT_TRUE(matrix_weighted[1].has_value());
  expect_input_error([&] { parse_curves_json(R"({"curves": []})", "named.json"); }, {"named.json", "empty list"});
}

TEST_F(IoCurvesJson, RefusesAnUnreadableFile) {
  const std::string missing = scratch.path("no-such.json");
  expect_input_error([&] { read_curves_json(missing); }, {missing, "cannot read"});
  // A directory opens like a file on Linux and fails on the first read.
  const std::string directory = scratch.root().string();
  expect_input_error([&] { read_curves_json(directory); }, {directory, "cannot read"});
}

TEST_F(IoCurvesJson, MalformedJsonNamesTheBytePosition) {
  // The missing comma sits on line 3; the parser notices at the '{' of the second curve, the
  // 62nd byte counted by hand ('{"curves": [\n' = 13, line 2 = 45 + newline, 2 spaces, then '{').
  expect_refused("{\"curves\": [\n  {\"id\": \"a\", \"kind\": \"bezier\", \"points\": []}\n  {\"id\": \"b\"}]}",
                 {"malformed JSON", "byte 62", "line 3"});
  expect_refused("{\"curves\": [", {"malformed JSON", "byte"});
  expect_refused("", {"malformed JSON"});
  expect_refused("{\"curves\": []} trailing", {"malformed JSON"});
}

TEST_F(IoCurvesJson, NanAndInfinityLiteralsAreMalformedAtTheirField) {
  expect_refused(R"({"curves": [{"id": "a", "kind": "bezier", "points": [[0, 0], [NaN, 1]]}]})",
                 {"malformed JSON", "curves[0].points[1][0]"});
  expect_refused(R"({"curves": [{"id": "a", "kind": "bezier", "points": [[0, 0], [1, Infinity]]}]})",
                 {"malformed JSON", "curves[0].points[1][1]"});
}

TEST_F(IoCurvesJson, NumberOverflowNamesTheField) {
  expect_refused("{\"curves\": [\n{\"id\": \"a\", \"kind\": \"rational_bezier\",\n"
                 " \"points\": [[0, 0], [1, 1]], \"weights\": [1, 1e999]}]}",
                 {"curves[0].weights[1]", "line 3", "overflow"});
  expect_refused(R"({"curves": [{"id": "a", "kind": "bezier", "points": [[0, 0], [-1e400, 1]]}]})",
                 {"curves[0].points[1][0]", "overflow"});
  // Finite factors whose product (the homogeneous coordinate w x) overflows.
  expect_refused(R"({"curves": [{"id": "a", "kind": "rational_bezier", "points": [[0, 0], [1e300, 1]], "weights": [1, 1e10]}]})",
                 {"curves[0] (id \"a\")", "points[1]", "weights[1]", "overflow"});
}

TEST_F(IoCurvesJson, RefusesAMissingOrEmptyCurveList) {
  expect_refused("[1, 2]", {"expected an object"});
  expect_refused("{}", {"curves: missing"});
  // A misspelt "curves" is named as such, not only as a missing list.
  expect_refused(R"({"curve": []})", {"\"curve\": unknown field"});
  expect_refused(R"({"curves": {"id": "a"}})", {"curves: expected an array, found an object"});
  expect_refused(R"({"curves": []})", {"curves: empty list"});
}

TEST_F(IoCurvesJson, RequiresAUniqueStringId) {
  expect_refused(R"({"curves": [{"kind": "bezier", "points": [[0, 0], [1, 1]]}]})", {"curves[0]", "id: missing"});
  expect_refused(R"({"curves": [{"id": "a", "kind": "bezier", "points": [[0, 0], [1, 1]]},
                                {"id": 7, "kind": "bezier", "points": [[0, 0], [1, 1]]}]})",
                 {"curves[1]", "id: expected a string, found a number"});
  expect_refused(R"({"curves": [{"id": "", "kind": "bezier", "points": [[0, 0], [1, 1]]}]})", {"curves[0]", "id: empty"});
  expect_refused(R"({"curves": [{"id": "a", "kind": "bezier", "points": [[0, 0], [1, 1]]},
                                {"id": "a", "kind": "bezier", "points": [[0, 0], [2, 1]]}]})",
                 {"curves[1] (id \"a\")", "duplicate of curves[0]"});
  // POINTS.csv could never name this curve.
  expect_refused(R"({"curves": [{"id": "a,b", "kind": "bezier", "points": [[0, 0], [1, 1]]}]})",
                 {"curves[0] (id \"a,b\")", "id: must not contain"});
}

TEST_F(IoCurvesJson, RefusesAnUnknownOrMistypedKind) {
  expect_refused(R"({"curves": [{"id": "a", "kind": "spline", "points": [[0, 0], [1, 1]]}]})",
                 {"curves[0] (id \"a\")", "kind: unknown \"spline\""});
  expect_refused(R"({"curves": [{"id": "a", "points": [[0, 0], [1, 1]]}]})", {"curves[0] (id \"a\")", "kind: missing"});
  expect_refused(R"({"curves": [{"id": "a", "kind": 1, "points": [[0, 0], [1, 1]]}]})",
                 {"curves[0] (id \"a\")", "kind: expected a string"});
  expect_refused(R"({"curves": [{"id": "a", "kind": "bezier", "points": [[0, 0], [1, 1]], "weights": [1, 1]}]})",
                 {"curves[0] (id \"a\")", "weights: not a field of kind \"bezier\""});
}

TEST_F(IoCurvesJson, RefusesPointsThatAreNotXYPairsOfNumbers) {
  expect_refused(R"({"curves": [{"id": "a", "kind": "bezier", "points": "none"}]})",
                 {"curves[0] (id \"a\")", "points: expected an array"});
  expect_refused(R"({"curves": [{"id": "a", "kind": "bezier"}]})", {"curves[0] (id \"a\")", "points: missing"});
  expect_refused(R"({"curves": [{"id": "a", "kind": "bezier", "points": []}]})", {"points: empty list"});
  expect_refused(R"({"curves": [{"id": "a", "kind": "bezier", "points": [[0, 0], [1, 2, 3]]}]})",
                 {"curves[0] (id \"a\")", "points[1]: 3 coordinates, but points[0] has 2"});
  expect_refused(R"({"curves": [{"id": "a", "kind": "bezier", "points": [[0, 0], [1, 2, 3, 4]]}]})",
                 {"curves[0] (id \"a\")", "points[1]: expected [x, y] or [x, y, z], found an array of 4"});
  expect_refused(R"({"curves": [{"id": "a", "kind": "bezier", "points": [[0, 0], 5]}]})",
                 {"points[1]: expected [x, y] or [x, y, z], found a number"});
  expect_refused(R"({"curves": [{"id": "a", "kind": "bezier", "points": [[0, 0], ["1", 2]]}]})",
                 {"points[1][0]: expected a number, found a string"});
  expect_refused(R"({"curves": [{"id": "a", "kind": "bezier", "points": [[0, 0], [1, null]]}]})",
                 {"points[1][1]: expected a number, found a null"});
}

TEST_F(IoCurvesJson, RefusesListsOfMismatchedLength) {
  expect_refused(R"({"curves": [{"id": "w", "kind": "rational_bezier", "points": [[0, 0], [1, 1], [2, 0]], "weights": [1, 1]}]})",
                 {"curves[0] (id \"w\")", "weights: 2 weights for 3 points"});
  expect_refused(R"({"curves": [{"id": "r", "kind": "rational", "x_num": [0, 1], "x_den": [1, 1], "y_num": [0, 1], "y_den": [1, 1, 1]}]})",
                 {"curves[0] (id \"r\")", "y_den: 3 coefficients, but x_num has 2"});
  expect_refused(R"({"curves": [{"id": "r", "kind": "rational", "x_num": [0, 1], "x_den": [1, 1], "y_num": [0, 1]}]})",
                 {"curves[0] (id \"r\")", "y_den: missing"});
  expect_refused(R"({"curves": [{"id": "r", "kind": "rational", "x_num": [0, 1], "x_den": [1, true], "y_num": [0, 1], "y_den": [1, 1]}]})",
                 {"curves[0] (id \"r\")", "x_den[1]: expected a number, found a boolean"});
}

TEST_F(IoCurvesJson, ValidationFailuresNameTheCurve) {
  // Weights 1, -1: the denominator changes sign on [0,1], a pole on the segment.
  expect_refused(R"({"curves": [{"id": "ok", "kind": "bezier", "points": [[0, 0], [1, 1]]},
                                {"id": "pole", "kind": "rational_bezier", "points": [[0, 0], [1, 1]], "weights": [1, -1]}]})",
                 {"curves[1] (id \"pole\")", "weights"});
  // One control point: degree 0.
  expect_refused(R"({"curves": [{"id": "dot", "kind": "bezier", "points": [[0, 0]]}]})", {"curves[0] (id \"dot\")", "degree"});
}

TEST_F(IoCurvesJson, RefusesDuplicateKeys) {
  // json::parse would silently keep the second "weights".
  expect_refused(R"({"curves": [{"id": "a", "kind": "rational_bezier", "points": [[0, 0], [1, 1]], "weights": [1, 1], "weights": [1, 2]}]})",
                 {"curves[0]: duplicate key \"weights\""});
}

// ---------------------------------------------------------------------------------------------
// POINTS.csv

// Curves referred to by id or index; only the ids matter to the reader. The id "7" is there to
// show that an id wins over the index of the same spelling.
std::vector<Curve> three_curves() {
  std::vector<Curve> curves(3);
  curves[0].id = "a";
  curves[1].id = "b";
  curves[2].id = "7";
  return curves;
}

class IoPointsCsv : public ::testing::Test {
 protected:
  ScratchDirectory scratch{"bezinv-io-test-"};
  const std::vector<Curve> curves = three_curves();

  std::vector<PointRow> read(std::string_view csv) {
    return detail::read_points_csv(scratch.write("points.csv", csv), curves);
  }
  void expect_refused(std::string_view csv, std::initializer_list<std::string> fragments) {
    const std::string path = scratch.write("points.csv", csv);
    expect_input_error([&] { detail::read_points_csv(path, curves); }, fragments);
    expect_input_error([&] { detail::read_points_csv(path, curves); }, {path});
  }
};

TEST_F(IoPointsCsv, ReadsIdsIndicesAndExactNumbers) {
  const auto rows = read("curve,x,y\n"
                         "a,0.1,-2.5e-3\n"
                         "b,1e-300,123456789.125\n"
                         "1,-0,+1.5\n"
                         "7,3,4\n"
                         "2,5,6\n"
                         " a , 1 ,\t2 \n"
                         "a,1e-400,-4e-320\n"
                         "a,.5,1.\n");
  ASSERT_EQ(rows.size(), 8u);
  const int expected_curve[] = {0, 1, 1, 2, 2, 0, 0, 0};
  const double expected_x[] = {0.1, 1e-300, -0.0, 3, 5, 1, 0.0, 0.5};
  const double expected_y[] = {-2.5e-3, 123456789.125, 1.5, 4, 6, 2, -4e-320, 1.0};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].curve, expected_curve[i]) << "row " << i;
    // Bit-exact: the same decimal must give the same double as the compiler's reading of it.
    EXPECT_EQ(std::bit_cast<std::uint64_t>(rows[i].point.x), std::bit_cast<std::uint64_t>(expected_x[i])) << "row " << i;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(rows[i].point.y), std::bit_cast<std::uint64_t>(expected_y[i])) << "row " << i;
    EXPECT_STREQ(rows[i].reason, "") << "row " << i;
  }
}

TEST_F(IoPointsCsv, BadRowsKeepTheirPositionWithAReason) {
  const auto rows = read("curve,x,y\n"
                         "a,1,2\n"        // 0 good
                         "zzz,1,2\n"      // 1 unknown id
                         "3,1,2\n"        // 2 index past the end (3 curves)
                         "-1,1,2\n"       // 3 negative index
                         ",1,2\n"         // 4 no curve
                         "a,abc,2\n"      // 5 x not a number
                         "a,1,nan\n"      // 6 y not finite
                         "a,1e999,2\n"    // 7 x overflows
                         "a,1,-inf\n"     // 8
                         "a,,2\n"         // 9 empty x
                         "a,1e5x,2\n"     // 10 trailing junk
                         "a,1,2 3\n"      // 11 two numbers in one field
                         "99999999999999999999999,1,2\n"  // 12 index beyond any integer type
                         "b,3,4\n");      // 13 good
  ASSERT_EQ(rows.size(), 14u);
  const char* const expected[] = {"",
                                  "unknown curve id",
                                  "curve index past the end",
                                  "negative curve index",
                                  "missing curve id",
                                  "x is not a number",
                                  "y is not finite",
                                  "x is not finite",
                                  "y is not finite",
                                  "x is not a number",
                                  "x is not a number",
                                  "y is not a number",
                                  "curve index past the end",
                                  ""};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_STREQ(rows[i].reason, expected[i]) << "row " << i;
    if (*expected[i] != '\0') {
      EXPECT_EQ(rows[i].curve, -1) << "row " << i;
    }
  }
  EXPECT_EQ(rows[0].curve, 0);
  EXPECT_EQ(rows[13].curve, 1);
  EXPECT_EQ(rows[13].point.x, 3.0);
  EXPECT_EQ(rows[13].point.y, 4.0);
}

TEST_F(IoPointsCsv, AcceptsCrlfBomSpacedHeaderAndATrailingBlankLine) {
  const auto rows = read("\xEF\xBB\xBF curve , x ,y\r\na,0.25,0.5\r\nb,-1,2\r\n\r\n");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].curve, 0);
  EXPECT_EQ(rows[0].point.x, 0.25);
  EXPECT_EQ(rows[0].point.y, 0.5);
  EXPECT_EQ(rows[1].curve, 1);
  EXPECT_EQ(rows[1].point.x, -1.0);
  EXPECT_EQ(rows[1].point.y, 2.0);  // CR not left on the last field

  EXPECT_EQ(read("curve,x,y\na,1,2").size(), 1u);  // no final newline
  EXPECT_EQ(read("curve,x,y\n").size(), 0u);       // header only: no points, not an error
}

TEST_F(IoPointsCsv, ReadsRfc4180QuotedFieldsLikeTheirUnquotedValues) {
  // Spreadsheets and csv.QUOTE_ALL writers quote every field, header included.
  const auto quoted = read("\"curve\",\"x\",\"y\"\n"
                           "\"a\",\"2\",\"1.5\"\n"
                           "\"b\" , \" -1e-3 \",\"+4\"\n"  // blanks outside and inside the quotes
                           "\"7\",3,\"4\"\n"                 // quoted and bare fields mixed
                           "\"1\",\"5\",6\r\n");
  const auto bare = read("curve,x,y\na,2,1.5\nb,-1e-3,+4\n7,3,4\n1,5,6\n");
  ASSERT_EQ(quoted.size(), bare.size());
  for (std::size_t i = 0; i < bare.size(); ++i) {
    EXPECT_EQ(quoted[i].curve, bare[i].curve) << "row " << i;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(quoted[i].point.x), std::bit_cast<std::uint64_t>(bare[i].point.x)) << "row " << i;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(quoted[i].point.y), std::bit_cast<std::uint64_t>(bare[i].point.y)) << "row " << i;
    EXPECT_STREQ(quoted[i].reason, "") << "row " << i;
  }
}

TEST_F(IoPointsCsv, QuotedCommasAndDoubledQuotesStayInTheirField) {
  // Each row has three fields: a comma or a doubled quote inside quotes is text, so these rows
  // are per-row problems (no id has commas or quotes), not a wrong field count for the file.
  const auto rows = read("curve,x,y\n"
                         "\"a,b\",1,2\n"         // 0 an id with a comma
                         "\"a\"\"\",1,2\n"       // 1 the id a"
                         "a,\"1,5\",2\n"         // 2 a decimal comma
                         "a,1,\"2\"\"\"\n"       // 3 2"
                         "\"\",1,2\n"            // 4 empty quoted id
                         "a,\"\",2\n"            // 5 empty quoted x
                         "\"\"\"\"\"\",1,2\n"    // 6 the id ""
                         "a\"b,1,2\n"            // 7 a quote inside a bare field is text
                         "\"a\",\"1\",\"2\"\n");  // 8 good
  const char* const expected[] = {"unknown curve id", "unknown curve id", "x is not a number", "y is not a number",
                                  "missing curve id", "x is not a number", "unknown curve id", "unknown curve id", ""};
  ASSERT_EQ(rows.size(), std::size(expected));
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_STREQ(rows[i].reason, expected[i]) << "row " << i;
  EXPECT_EQ(rows[8].curve, 0);
  EXPECT_EQ(rows[8].point.x, 1.0);
  // Commas inside quotes do not count as separators; outside they do.
  expect_refused("curve,x,y\n\"a\",\"1\",\"2\",\"3,4\"\n", {":2:", "expected 3 fields (curve,x,y), found 4"});
  expect_refused("\"curve,x\",y\n", {":1:", "header must be 'curve,x,y'"});
}

TEST_F(IoPointsCsv, RefusesUnreadableOrEmptyFiles) {
  const std::string missing = scratch.path("no-such.csv");
  expect_input_error([&] { detail::read_points_csv(missing, curves); }, {missing, "cannot read"});
  // A directory: its reported size is not a file size (this once ended in std::bad_alloc).
  const std::string directory = scratch.root().string();
  expect_input_error([&] { detail::read_points_csv(directory, curves); }, {directory, "cannot read"});
  expect_refused("", {":1:", "empty"});
  expect_refused("\xEF\xBB\xBF", {":1:", "empty"});
  expect_refused("\n\n", {":1:", "empty"});
}

TEST_F(IoPointsCsv, RefusesAMissingOrWrongHeader) {
  expect_refused("a,1,2\nb,3,4\n", {":1:", "header must be 'curve,x,y'", "\"a,1,2\""});
  expect_refused("curve,x\na,1\n", {":1:", "header"});
  expect_refused("curve,x,y,w\na,1,2,3\n", {":1:", "header must be 'curve,x,y' or 'curve,x,y,z'"});
  expect_refused("curve,y,x\na,1,2\n", {":1:", "header"});
  expect_refused("Curve,X,Y\na,1,2\n", {":1:", "header"});
}

TEST_F(IoPointsCsv, RefusesRowsWithTheWrongNumberOfFields) {
  expect_refused("curve,x,y\na,1,2\na,1\nb,1,2\n", {":3:", "expected 3 fields", "found 2"});
  expect_refused("curve,x,y\na,1,2\nb,1,2\na,1,2,3\n", {":4:", "found 4"});
  // A blank line with rows after it is not "the end of the file".
  expect_refused("curve,x,y\na,1,2\n\nb,1,2\n", {":3:", "found 1", "blank line"});
  expect_refused("curve,x,y\r\na,1,2\r\n\r\nb,1,2\r\n", {":3:", "blank line"});
}

// ---------------------------------------------------------------------------------------------
// OUT.csv


class IoResultsCsv : public ::testing::Test {
 protected:
  ScratchDirectory scratch{"bezinv-io-test-"};

  std::vector<std::string> directory_entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(scratch.root())) names.push_back(entry.path().filename().string());
    return names;
  }
};

TEST_F(IoResultsCsv, WritesDoublesThatReadBackBitExactly) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double awkward[] = {0.1,  1.0 / 3.0, 0.25,  -0.0, 5e-324, 1e-310, std::numeric_limits<double>::max(),
                            -2.0 / 3.0 * 1e-200, 1.0 - 0x1p-53, 1e22, 0.30000000000000004};
  std::vector<PointResult> results;
  for (double value : awkward) {
    PointResult r;
    r.t = value;
    r.residual = value * 0.5;
    r.t2 = nan;
    r.sigma_min = -value;
    r.sigma_next = value * 3.0;
    r.status = Status::ok;
    r.path = Path::bezout;
    results.push_back(r);
  }
  const std::string out = scratch.path("out.csv");
  write_results_csv(out, results);

  const std::vector<std::string> lines = split(read_file(out), '\n');
  ASSERT_EQ(lines.size(), results.size() + 2);  // header, rows, "" after the final newline
  EXPECT_EQ(lines.front(), "t,status,residual,t2,sigma_min,sigma_next,path,reason");
  EXPECT_EQ(lines.back(), "");
  for (std::size_t i = 0; i < results.size(); ++i) {
    const std::vector<std::string> fields = split(lines[i + 1], ',');
    ASSERT_EQ(fields.size(), 8u) << lines[i + 1];
    const double written[] = {results[i].t, results[i].residual, nan, results[i].sigma_min, results[i].sigma_next};
    const std::size_t column[] = {0, 2, 3, 4, 5};
    for (std::size_t k = 0; k < 5; ++k) {
      const double back = std::strtod(fields[column[k]].c_str(), nullptr);
      if (std::isnan(written[k])) {
        EXPECT_EQ(fields[column[k]], "nan");
      } else {
        EXPECT_TRUE(same_bits(back, written[k])) << fields[column[k]] << " vs " << written[k];
      }
    }
    EXPECT_EQ(fields[1], "ok");
    EXPECT_EQ(fields[6], to_string(Path::bezout));
    EXPECT_EQ(fields[7], "");
  }
}

TEST_F(IoResultsCsv, WritesStatusesReasonsAndQuotesAReasonWithAComma) {
  PointResult bad;
  bad.status = Status::invalid_input;
  bad.reason = "unknown curve id";
  PointResult quoted;
  quoted.status = Status::failed;
  quoted.reason = "degenerate, \"really\"";  // must stay one CSV field (RFC 4180)
  PointResult off;
  off.status = Status::off_curve;
  off.t = 0.5;
  std::vector<PointResult> results{bad, quoted, off};
  const std::string out = scratch.path("out.csv");
  write_results_csv(out, results);
  const std::vector<std::string> lines = split(read_file(out), '\n');
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[1], "nan,invalid_input,nan,nan,nan,nan," + std::string(to_string(Path::none)) + ",unknown curve id");
  EXPECT_EQ(lines[2], "nan,failed,nan,nan,nan,nan," + std::string(to_string(Path::none)) + ",\"degenerate, \"\"really\"\"\"");
  EXPECT_EQ(lines[3], "0.5,off_curve,nan,nan,nan,nan," + std::string(to_string(Path::none)) + ",");
}

TEST_F(IoResultsCsv, EmptyResultsGiveTheHeaderOnly) {
  const std::string out = scratch.path("out.csv");
  write_results_csv(out, {});
  EXPECT_EQ(read_file(out), "t,status,residual,t2,sigma_min,sigma_next,path,reason\n");
}

TEST_F(IoResultsCsv, ReplacesAnExistingFileWholeAndLeavesNoTemporary) {
  const std::string out = scratch.write("out.csv", "stale contents that are longer than the new file\n");
  write_results_csv(out, {});
  EXPECT_EQ(read_file(out), "t,status,residual,t2,sigma_min,sigma_next,path,reason\n");
  EXPECT_EQ(directory_entries(), std::vector<std::string>{"out.csv"});
}

TEST_F(IoResultsCsv, FailureLeavesNoFile) {
  const std::vector<PointResult> results(3);
  // Target in a directory that does not exist.
  const std::string nowhere = scratch.path("missing-dir/out.csv");
  expect_input_error([&] { write_results_csv(nowhere, results); }, {nowhere, "cannot write"});
  EXPECT_FALSE(fs::exists(scratch.root() / "missing-dir"));

  // Target is a directory: the temporary file is written, the rename fails, and the temporary
  // must be gone afterwards.
  fs::create_directory(scratch.root() / "taken");
  const std::string taken = scratch.path("taken");
  expect_input_error([&] { write_results_csv(taken, results); }, {taken, "cannot write"});
  EXPECT_EQ(directory_entries(), std::vector<std::string>{"taken"});
  EXPECT_TRUE(fs::is_empty(scratch.root() / "taken"));
}

}  // namespace
}  // namespace bezinv
