// .npy points and results, curve selection, and streaming in chunks (io.hpp). Every .npy input is
// built here byte by byte from the format description (not by the writer under test), and every
// .npy output is taken apart here byte by byte, so reader and writer are checked independently.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "support/bits.hpp"
#include "bezinv/io.hpp"
#include "bezinv/plan.hpp"
#include "support/expect_input_error.hpp"
#include "support/npy_bytes.hpp"
#include "support/scratch_directory.hpp"
#include "support/split.hpp"

namespace bezinv {
namespace {

using test_support::same_bits;

namespace fs = std::filesystem;

using test_support::read_file;
using test_support::ScratchDirectory;
using test_support::split;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

using test_support::expect_input_error;

using test_support::le_bytes;
using test_support::npy_bytes;
using test_support::npy_dict;

std::vector<Curve> curves_a_b_7() {
  std::vector<Curve> curves(3);
  curves[0].id = "a";
  curves[1].id = "b";
  curves[2].id = "7";
  return curves;
}

std::vector<PointRow> read_all(PointReader& reader, std::size_t chunk = 2) {
  std::vector<PointRow> rows, part(chunk);
  while (const std::size_t got = reader.read(part)) rows.insert(rows.end(), part.begin(), part.begin() + got);
  return rows;
}


class NpyPoints : public ::testing::Test {
 protected:
  ScratchDirectory scratch{"bezinv-npy-test-"};
  const std::vector<Curve> curves = curves_a_b_7();
  // Five points, one of them with a NaN x and one with an infinite y.
  const std::string points =
      scratch.write("points.npy", npy_bytes(npy_dict("'<f8'", "(5, 2)"), le_bytes<double>({0.1, -2.5e-3, 1e-300, 123456789.125,
                                                                                      kNan, 1, 3, INFINITY, -0.0, 5e-324})));

  void expect_refused(const std::string& name, const std::string& bytes, const CurveSelection& selection,
                      std::initializer_list<std::string> fragments) {
    const std::string path = scratch.write(name, bytes);
    expect_input_error([&] { open_points(path, curves, selection); }, fragments);
  }
};

TEST_F(NpyPoints, ReadsExactNumbersForTheCurveGivenByIdOrIndex) {
  for (const std::string& selection : {std::string("b"), std::string("1")}) {
    const auto reader = open_points(points, curves, {selection, ""});
    EXPECT_EQ(reader->progress().points_total, 5u);
    const std::vector<PointRow> rows = read_all(*reader);
    ASSERT_EQ(rows.size(), 5u);
    const double x[] = {0.1, 1e-300, kNan, 3, -0.0};
    const double y[] = {-2.5e-3, 123456789.125, 1, INFINITY, 5e-324};
    const char* reason[] = {"", "", "x is not finite", "y is not finite", ""};
    for (std::size_t i = 0; i < rows.size(); ++i) {
      EXPECT_TRUE(same_bits(rows[i].point.x, x[i])) << i;
      EXPECT_TRUE(same_bits(rows[i].point.y, y[i])) << i;
      EXPECT_STREQ(rows[i].reason, reason[i]) << i;
      EXPECT_EQ(rows[i].curve, *reason[i] ? -1 : 1) << i;
    }
    EXPECT_EQ(reader->progress().points, 5u);
  }
  // "7" is an id before it is an index.
  EXPECT_EQ(read_all(*open_points(points, curves, {"7", ""}))[0].curve, 2);
}

TEST_F(NpyPoints, ReadsVersion2HeadersAndEmptyArrays) {
  const std::string v2 = scratch.write("v2.npy", npy_bytes(npy_dict("'<f8'", "(1, 2)"), le_bytes<double>({1.5, 2.5}), 2));
  const std::vector<PointRow> rows = read_all(*open_points(v2, curves, {"a", ""}));
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].point.x, 1.5);
  EXPECT_EQ(rows[0].point.y, 2.5);
  const std::string empty = scratch.write("empty.npy", npy_bytes(npy_dict("'<f8'", "(0, 2)"), ""));
  EXPECT_TRUE(read_all(*open_points(empty, curves, {"a", ""})).empty());
}

TEST_F(NpyPoints, CurveIndexFileInt32AndInt64) {
  const std::string i32 = scratch.write("i32.npy", npy_bytes(npy_dict("'<i4'", "(5,)"), le_bytes<std::int32_t>({2, 0, 1, -1, 3})));
  const std::string i64 = scratch.write(
      "i64.npy", npy_bytes(npy_dict("'<i8'", "(5,)"), le_bytes<std::int64_t>({2, 0, 1, std::int64_t{1} << 40, -(std::int64_t{1} << 40)})));
  const std::vector<PointRow> a = read_all(*open_points(points, curves, {"", i32}));
  ASSERT_EQ(a.size(), 5u);
  EXPECT_EQ(a[0].curve, 2);
  EXPECT_EQ(a[1].curve, 0);
  EXPECT_EQ(a[2].curve, -1);  // its own x is NaN
  EXPECT_STREQ(a[2].reason, "x is not finite");
  EXPECT_STREQ(a[3].reason, "negative curve index");
  EXPECT_STREQ(a[4].reason, "curve index past the end");
  const std::vector<PointRow> b = read_all(*open_points(points, curves, {"", i64}));
  ASSERT_EQ(b.size(), 5u);
  EXPECT_EQ(b[0].curve, 2);
  EXPECT_EQ(b[1].curve, 0);
  EXPECT_STREQ(b[3].reason, "curve index past the end");
  EXPECT_STREQ(b[4].reason, "negative curve index");
}

TEST_F(NpyPoints, HeaderErrorsNameTheFileAndTheField) {
  const std::string data = le_bytes<double>({1, 2, 3, 4, 5, 6});
  const CurveSelection a{"a", ""};
  expect_refused("f4.npy", npy_bytes(npy_dict("'<f4'", "(3, 2)"), data), a, {"f4.npy: header: dtype '<f4' is not '<f8'"});
  expect_refused("be.npy", npy_bytes(npy_dict("'>f8'", "(3, 2)"), data), a, {"be.npy: header: dtype '>f8' is not '<f8'"});
  expect_refused("rec.npy", npy_bytes(npy_dict("[('x', '<f8'), ('y', '<f8')]", "(3,)"), data), a,
                 {"rec.npy: header: dtype [('x', '<f8'), ('y', '<f8')] is not '<f8'"});
  expect_refused("fortran.npy", npy_bytes(npy_dict("'<f8'", "(3, 2)", "True"), data), a,
                 {"fortran.npy: header: fortran_order is True"});
  expect_refused("flat.npy", npy_bytes(npy_dict("'<f8'", "(6,)"), data), a, {"flat.npy: header: shape (6,) is not (N, 2)"});
  expect_refused("wide.npy", npy_bytes(npy_dict("'<f8'", "(1, 4)"), data), a, {"wide.npy: header: shape (1, 4) is not (N, 2) or (N, 3)"});
  // (N, 3) is a space curve's points: with --curve naming a plane curve, the whole file is refused.
  expect_refused("space.npy", npy_bytes(npy_dict("'<f8'", "(2, 3)"), data), a,
                 {"space.npy: header: shape (2, 3): curve", "is a plane curve, whose points are (N, 2)"});
  expect_refused("short.npy", npy_bytes(npy_dict("'<f8'", "(4, 2)"), data), a,
                 {"short.npy: data: truncated", "(4, 2)", "needs 64 bytes", "the file has 48"});
  expect_refused("long.npy", npy_bytes(npy_dict("'<f8'", "(2, 2)"), data), a, {"long.npy: data: 16 bytes after the end"});
  expect_refused("nodescr.npy", npy_bytes("{'fortran_order': False, 'shape': (3, 2), }", data), a,
                 {"nodescr.npy: header: missing 'descr'"});
  expect_refused("garbled.npy", npy_bytes("{'descr': '<f8', 'fortran_order': Maybe, 'shape': (3, 2), }", data), a,
                 {"garbled.npy: header: malformed dict", "True or False"});
  expect_refused("text.npy", "x,y\n1,2\n", a, {"text.npy: not a .npy file"});
  expect_refused("v9.npy", npy_bytes(npy_dict("'<f8'", "(3, 2)"), data).replace(6, 1, "\x09"), a,
                 {"v9.npy: header: unsupported format version 9.0"});
  expect_refused("cut.npy", npy_bytes(npy_dict("'<f8'", "(3, 2)"), data).substr(0, 40), a, {"cut.npy: header: truncated"});
  expect_input_error([&] { open_points(scratch.path("absent.npy"), curves, a); }, {"absent.npy: cannot read"});
}

TEST_F(NpyPoints, CurveSelectionErrors) {
  expect_input_error([&] { open_points(points, curves, {}); }, {"points.npy", "--curve ID or --curve-index"});
  expect_input_error([&] { open_points(points, curves, {"zz", ""}); }, {"points.npy", "--curve 'zz'"});
  expect_input_error([&] { open_points(points, curves, {"3", ""}); }, {"points.npy", "--curve '3'"});
  const std::string index = scratch.write("i.npy", npy_bytes(npy_dict("'<i4'", "(5,)"), le_bytes<std::int32_t>({0, 0, 0, 0, 0})));
  expect_input_error([&] { open_points(points, curves, {"a", index}); }, {"not both"});
  // The index array: wrong dtype, wrong shape, wrong length (whole-file errors naming it).
  const CurveSelection wrong_dtype{"", scratch.write("u8.npy", npy_bytes(npy_dict("'<u8'", "(5,)"), std::string(40, '\0')))};
  expect_input_error([&] { open_points(points, curves, wrong_dtype); }, {"u8.npy: header: dtype '<u8' is not '<i4' or '<i8'"});
  const CurveSelection wrong_shape{"", scratch.write("2d.npy", npy_bytes(npy_dict("'<i4'", "(5, 1)"), std::string(20, '\0')))};
  expect_input_error([&] { open_points(points, curves, wrong_shape); }, {"2d.npy: header: shape (5, 1) is not (N,)"});
  const CurveSelection wrong_length{"", scratch.write("4.npy", npy_bytes(npy_dict("'<i4'", "(4,)"), std::string(16, '\0')))};
  expect_input_error([&] { open_points(points, curves, wrong_length); },
                     {"4.npy: header: shape (4,) does not match the 5 points of", "points.npy"});
  const CurveSelection cut{"", scratch.write("cut.npy", npy_bytes(npy_dict("'<i8'", "(5,)"), std::string(16, '\0')))};
  expect_input_error([&] { open_points(points, curves, cut); }, {"cut.npy: data: truncated"});
  // A CSV names its curves itself.
  const std::string csv = scratch.write("points.csv", "curve,x,y\na,1,2\n");
  expect_input_error([&] { open_points(csv, curves, {"a", ""}); }, {"points.csv", "--curve"});
  expect_input_error([&] { open_points(csv, curves, {"", index}); }, {"points.csv", "--curve-index"});
}

// ---------------------------------------------------------------------------------------------
// OUT.npy, taken apart by hand.

struct ParsedNpy {
  std::string dict;
  std::size_t data_offset = 0;
  std::string data;
};

ParsedNpy parse_npy(const std::string& bytes) {
  ParsedNpy parsed;
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  const std::size_t length = static_cast<unsigned char>(bytes[8]) | static_cast<unsigned char>(bytes[9]) << 8;
  parsed.dict = bytes.substr(10, length);
  parsed.data_offset = 10 + length;
  parsed.data = bytes.substr(parsed.data_offset);
  return parsed;
}

double double_at(const std::string& data, std::size_t offset) {
  std::uint64_t bits = 0;
  for (std::size_t i = 0; i < 8; ++i) bits |= std::uint64_t{static_cast<unsigned char>(data[offset + i])} << (8 * i);
  return std::bit_cast<double>(bits);
}

TEST(NpyResults, WriterOutputIsAStructuredArrayNumpyCanRead) {
  ScratchDirectory scratch{"bezinv-npy-test-"};
  std::vector<PointResult> results(7);
  for (std::size_t i = 0; i < results.size(); ++i) {
    results[i].t = 0.1 * static_cast<double>(i);
    results[i].residual = 1e-17 * static_cast<double>(i);
    results[i].t2 = i == 2 ? 0.75 : kNan;
    results[i].sigma_min = -5e-324;
    results[i].sigma_next = std::numeric_limits<double>::max();
    results[i].status = static_cast<Status>(i % 6);
    results[i].path = static_cast<Path>(i % 6);
  }
  const std::string out = scratch.path("out.npy");
  {
    const auto writer = open_results(out);
    writer->write(std::span(results).first(3));  // in two pieces: the count is the sum
    writer->write(std::span(results).subspan(3));
    writer->commit();
  }
  const ParsedNpy npy = parse_npy(read_file(out));
  EXPECT_EQ(npy.data_offset % 64, 0u);  // numpy aligns the data
  EXPECT_EQ(npy.dict.back(), '\n');
  EXPECT_TRUE(npy.dict.starts_with("{'descr': [('t', '<f8'), ('residual', '<f8'), ('t2', '<f8'), ('sigma_min', '<f8'), "
                                   "('sigma_next', '<f8'), ('status', '|u1'), ('path', '|u1')], "
                                   "'fortran_order': False, 'shape': (7,), }"))
      << npy.dict;
  ASSERT_EQ(npy.data.size(), results.size() * 42);
  for (std::size_t i = 0; i < results.size(); ++i) {
    const std::size_t r = 42 * i;
    EXPECT_TRUE(same_bits(double_at(npy.data, r), results[i].t)) << i;
    EXPECT_TRUE(same_bits(double_at(npy.data, r + 8), results[i].residual)) << i;
    EXPECT_TRUE(same_bits(double_at(npy.data, r + 16), results[i].t2)) << i;
    EXPECT_TRUE(same_bits(double_at(npy.data, r + 24), results[i].sigma_min)) << i;
    EXPECT_TRUE(same_bits(double_at(npy.data, r + 32), results[i].sigma_next)) << i;
    EXPECT_EQ(npy.data[r + 40], static_cast<char>(i % 6)) << i;  // the Status enum value
    EXPECT_EQ(npy.data[r + 41], static_cast<char>(i % 6)) << i;  // the Path enum value
  }
  // The documented codes are the enum order.
  EXPECT_EQ(static_cast<int>(Status::invalid_input), 4);
  EXPECT_EQ(static_cast<int>(Path::nearest), 4);
  EXPECT_EQ(static_cast<int>(Path::bezout_lu), 5);
}

TEST(NpyResults, AWriterNeverCommittedLeavesNothing) {
  ScratchDirectory scratch{"bezinv-npy-test-"};
  scratch.write("out.npy", "stale");
  {
    const auto writer = open_results(scratch.path("out.npy"));
    writer->write(std::vector<PointResult>(3));
  }
  EXPECT_EQ(read_file(scratch.path("out.npy")), "stale");
  EXPECT_EQ(std::distance(fs::directory_iterator(scratch.root()), fs::directory_iterator()), 1);
}

// ---------------------------------------------------------------------------------------------
// Streaming: chunk boundaries and a failure in the middle.

constexpr const char* kCurvesJson = R"({"curves": [
  {"id": "cubic", "kind": "bezier", "points": [[0, 0], [1, 2], [3, 2], [4, 0]]},
  {"id": "line", "kind": "bezier", "points": [[0, 0], [2, 1]]}
]})";

class Stream : public ::testing::Test {
 protected:
  ScratchDirectory scratch{"bezinv-stream-test-"};
  std::vector<Curve> curves = read_curves_json(scratch.write("curves.json", kCurvesJson));
  std::vector<InversionPlan> plans = [this] {
    std::vector<InversionPlan> made;
    for (const Curve& curve : curves) made.push_back(make_plan(curve));
    return made;
  }();

  std::string run(const std::string& points, const std::string& out, std::size_t chunk, const CurveSelection& selection = {}) {
    const auto reader = open_points(points, curves, selection);
    const auto writer = open_results(out, 1);
    std::size_t calls = 0;
    std::uint64_t last = 0;
    const StreamSummary summary = invert_stream(*reader, *writer, plans, {}, chunk, [&](const ReadProgress& p) {
      ++calls;
      EXPECT_GT(p.points, last);  // progress only moves forward
      last = p.points;
    });
    writer->commit();
    EXPECT_EQ(last, summary.points);
    EXPECT_EQ(calls, (summary.points + chunk - 1) / chunk);  // chunks this small: one slice each
    return read_file(out);
  }
};

TEST_F(Stream, ChunkBoundariesKeepEveryRowInOrder) {
  // Line points at t = i/10 (exact answers), with bad rows on and around the chunk boundaries.
  std::string csv = "curve,x,y\n";
  for (int i = 0; i <= 10; ++i) {
    csv += "line," + std::to_string(0.2 * i) + "," + std::to_string(0.1 * i) + "\n";
    if (i == 2 || i == 3 || i == 8) csv += "nope,1,1\n";
  }
  const std::string points = scratch.write("points.csv", csv);
  const std::string whole = run(points, scratch.path("whole.csv"), 1000);
  for (std::size_t chunk : {1, 2, 3, 7, 14}) EXPECT_EQ(run(points, scratch.path("chunked.csv"), chunk), whole) << chunk;

  const std::vector<std::string> lines = split(whole, '\n');
  ASSERT_EQ(lines.size(), 1 + 14 + 1u);
  std::size_t row = 1;
  for (int i = 0; i <= 10; ++i) {
    const std::vector<std::string> fields = split(lines[row++], ',');
    EXPECT_EQ(fields[1], "ok") << i;
    EXPECT_NEAR(std::stod(fields[0]), 0.1 * i, 1e-12) << i;
    if (i == 2 || i == 3 || i == 8) {
      EXPECT_EQ(lines[row++], "nan,invalid_input,nan,nan,nan,nan,none,unknown curve id");
    }
  }
}

TEST_F(Stream, NpyChunksMatchTheWholeRun) {
  std::string data;
  for (int i = 0; i < 10; ++i) data += le_bytes<double>({0.2 * i, 0.1 * i});
  const std::string points = scratch.write("points.npy", npy_bytes(npy_dict("'<f8'", "(10, 2)"), data));
  const std::string whole = run(points, scratch.path("whole.npy"), 64, {"line", ""});
  EXPECT_EQ(run(points, scratch.path("chunked.npy"), 3, {"line", ""}), whole);
  const ParsedNpy npy = parse_npy(whole);
  EXPECT_NE(npy.dict.find("'shape': (10,)"), std::string::npos);
  ASSERT_EQ(npy.data.size(), 10 * 42u);
  for (int i = 0; i < 10; ++i) {
    EXPECT_NEAR(double_at(npy.data, 42 * i), 0.1 * i, 1e-12);
    EXPECT_EQ(npy.data[42 * i + 40], 0);  // ok
  }
}

TEST_F(Stream, AFailureMidStreamLeavesNoOutputAndNoTemporary) {
  std::string csv = "curve,x,y\n";
  for (int i = 0; i < 20; ++i) csv += "line,1,0.5\n";
  csv += "line,1\n";  // line 22
  for (int i = 0; i < 5; ++i) csv += "line,1,0.5\n";
  const std::string points = scratch.write("points.csv", csv);
  for (const char* name : {"out.csv", "out.npy"}) {
    const std::string out = scratch.path(name);
    expect_input_error([&] { run(points, out, 3); }, {"points.csv:22:", "expected 3 fields"});
    EXPECT_FALSE(fs::exists(out)) << name;
  }
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(scratch.root())) left.push_back(entry.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"curves.json", "points.csv"}));
}

TEST_F(Stream, CsvLinesSpanningReadBlocks) {
  // More than one 4 MiB read block, so lines are cut at block ends; every row must come back.
  std::string csv = "curve,x,y\n";
  constexpr int kRows = 300000;
  for (int i = 0; i < kRows; ++i) csv += "line," + std::to_string(i) + ".25,-" + std::to_string(i) + ".5\r\n";
  ASSERT_GT(csv.size(), std::size_t{5} << 20);
  const auto reader = open_points(scratch.write("big.csv", csv), curves);
  std::vector<PointRow> rows(4099);
  std::size_t seen = 0;
  while (const std::size_t got = reader->read(rows)) {
    for (std::size_t k = 0; k < got; ++k, ++seen) {
      ASSERT_EQ(rows[k].curve, 1) << seen;
      ASSERT_EQ(rows[k].point.x, static_cast<double>(seen) + 0.25) << seen;
      ASSERT_EQ(rows[k].point.y, -static_cast<double>(seen) - 0.5) << seen;
    }
  }
  EXPECT_EQ(seen, std::size_t{kRows});
  EXPECT_EQ(reader->progress().bytes, csv.size());
  EXPECT_EQ(reader->progress().bytes_total, csv.size());
}

TEST_F(Stream, CsvFilesAroundTheSmallReadStep) {
  // A regular file is read in steps of its size + 1 (at least 64 KiB, at most 4 MiB): files just
  // under, at and over a step, and a tiny one, give every row and see their end.
  for (const std::size_t size : {std::size_t{24}, std::size_t{65535}, std::size_t{65536}, std::size_t{65537},
                                 std::size_t{131073}}) {
    std::string rows;
    std::size_t count = 0;
    for (; 10 + rows.size() + 11 <= size; ++count) rows += "line,1,0.5\n";
    // The first row's x padded with leading zeros (still 1) to the exact size.
    std::string csv = "curve,x,y\nline," + std::string(size - 10 - rows.size(), '0') + rows.substr(5);
    ASSERT_EQ(csv.size(), size);
    const auto reader = open_points(scratch.write("sized.csv", csv), curves);
    std::vector<PointRow> got_rows(1000);
    std::size_t seen = 0;
    while (const std::size_t got = reader->read(got_rows)) {
      for (std::size_t k = 0; k < got; ++k, ++seen) {
        ASSERT_EQ(got_rows[k].curve, 1) << size << " " << seen;
        ASSERT_EQ(got_rows[k].point.x, 1.0) << size << " " << seen;
      }
    }
    EXPECT_EQ(seen, count) << size;
    EXPECT_EQ(reader->progress().bytes, size);
  }
}

}  // namespace
}  // namespace bezinv
