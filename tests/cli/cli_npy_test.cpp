// End to end with .npy files and streaming: the real `bezinv` binary. Points come from known
// parameters (de Casteljau in the test), .npy inputs are built byte by byte here and .npy outputs
// taken apart here, independently of the engine's reader and writer.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "support/de_casteljau.hpp"
#include "support/npy_bytes.hpp"
#include "support/run_bezinv.hpp"
#include "support/scratch_directory.hpp"
#include "support/split.hpp"

namespace {

namespace fs = std::filesystem;

using bezinv::test_support::read_file;
using bezinv::test_support::ScratchDirectory;
using bezinv::test_support::split;

using bezinv::test_support::Outcome;
using bezinv::test_support::quoted;
using bezinv::test_support::run_bezinv;

using bezinv::test_support::de_casteljau;
using bezinv::test_support::rational_de_casteljau;
using bezinv::test_support::Vec2;

const std::vector<Vec2> kCubic{{0, 0}, {1, 2}, {3, 2}, {4, 0}};
const std::vector<Vec2> kLine{{0, 0}, {2, 1}};

constexpr const char* kCubicAndLineJson = R"({"curves": [
  {"id": "cubic", "kind": "bezier", "points": [[0, 0], [1, 2], [3, 2], [4, 0]]},
  {"id": "line", "kind": "bezier", "points": [[0, 0], [2, 1]]}
]})";

using bezinv::test_support::append_le;
using bezinv::test_support::npy_file;

// One record of OUT.npy.
struct Record {
  double t, residual, t2, sigma_min, sigma_next;
  int status, path;
};

std::vector<Record> read_results_npy(const std::string& bytes, std::string* dict = nullptr) {
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  const std::size_t length = static_cast<unsigned char>(bytes[8]) | static_cast<unsigned char>(bytes[9]) << 8;
  if (dict) *dict = bytes.substr(10, length);
  const std::string data = bytes.substr(10 + length);
  EXPECT_EQ(data.size() % 42, 0u);
  std::vector<Record> records;
  for (std::size_t r = 0; r + 42 <= data.size(); r += 42) {
    double numbers[5];
    for (int k = 0; k < 5; ++k) {
      std::uint64_t bits = 0;
      for (int i = 0; i < 8; ++i) bits |= std::uint64_t{static_cast<unsigned char>(data[r + 8 * k + i])} << (8 * i);
      numbers[k] = std::bit_cast<double>(bits);
    }
    records.push_back({numbers[0], numbers[1], numbers[2], numbers[3], numbers[4], data[r + 40], data[r + 41]});
  }
  return records;
}

using bezinv::test_support::csv_number;

class CliNpy : public ::testing::Test {
 protected:
  ScratchDirectory scratch{"bezinv-cli-npy-test-"};
  std::string curves = scratch.write("curves.json", kCubicAndLineJson);
  // Known parameters on the cubic; a few off the segment / off the curve.
  const std::vector<double> params{0.0, 0.1, 0.25, 0.5, 0.6180339887, 0.75, 0.9, 1.0, 0.3, 0.45, 0.05};

  std::string points_npy() {
    std::string data;
    for (double t : params) {
      const Vec2 p = de_casteljau(kCubic, t);
      append_le(data, p[0]);
      append_le(data, p[1]);
    }
    // Built by appending: GCC 12 warns -Wrestrict (falsely) on "(" + std::to_string(...).
    std::string shape = std::to_string(params.size());
    shape.insert(shape.begin(), '(');
    shape += ", 2)";
    return scratch.write("points.npy", npy_file("<f8", shape, data));
  }

  std::string invert(const std::string& points, const std::string& out, const std::string& extra = "") {
    return "invert --curves '" + curves + "' --points '" + points + "' --out '" + out + "' " + extra;
  }

  std::vector<std::string> directory_entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(scratch.root())) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
};

TEST_F(CliNpy, NpyInNpyOutGivesTheKnownParameters) {
  const std::string points = points_npy();
  for (const char* chunk : {"", "--chunk-points 3"}) {
    const std::string out = scratch.path("out.npy");
    const Outcome run = run_bezinv(scratch, invert(points, out, "--curve cubic " + std::string(chunk)));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.err, "");  // not a terminal: no progress line
    std::string dict;
    const std::vector<Record> records = read_results_npy(read_file(out), &dict);
    EXPECT_NE(dict.find("'shape': (" + std::to_string(params.size()) + ",)"), std::string::npos) << dict;
    ASSERT_EQ(records.size(), params.size());
    for (std::size_t i = 0; i < params.size(); ++i) {
      EXPECT_EQ(records[i].status, 0) << i;  // ok
      EXPECT_NEAR(records[i].t, params[i], 1e-12) << i;
      EXPECT_LT(records[i].residual, 1e-12) << i;
      EXPECT_TRUE(std::isnan(records[i].t2)) << i;
      EXPECT_GE(records[i].path, 1) << i;  // some computation, not `none`
    }
  }
}

TEST_F(CliNpy, CurveIndexFileChoosesTheCurvePerPoint) {
  // Points alternate between the line (index 1) and the cubic (0); then a negative and a too-large index.
  std::string data, indices;
  const double ts[] = {0.2, 0.4, 0.6, 0.8, 0.5, 0.5};
  const std::int64_t curve_of[] = {1, 0, 1, 0, -3, 2};
  for (int i = 0; i < 6; ++i) {
    const Vec2 p = de_casteljau(curve_of[i] == 1 ? kLine : kCubic, ts[i]);
    append_le(data, p[0]);
    append_le(data, p[1]);
    append_le(indices, curve_of[i]);
  }
  const std::string points = scratch.write("p.npy", npy_file("<f8", "(6, 2)", data));
  const std::string index = scratch.write("i.npy", npy_file("<i8", "(6,)", indices));
  const std::string out = scratch.path("out.csv");
  const Outcome run = run_bezinv(scratch, invert(points, out, "--curve-index '" + index + "' --chunk-points 4"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::vector<std::string> lines = split(read_file(out), '\n');
  ASSERT_EQ(lines.size(), 8u);
  for (int i = 0; i < 4; ++i) {
    const std::vector<std::string> fields = split(lines[1 + i], ',');
    EXPECT_EQ(fields[1], "ok") << i;
    EXPECT_NEAR(std::stod(fields[0]), ts[i], 1e-12) << i;
  }
  EXPECT_EQ(lines[5], "nan,invalid_input,nan,nan,nan,nan,none,negative curve index");
  EXPECT_EQ(lines[6], "nan,invalid_input,nan,nan,nan,nan,none,curve index past the end");

  // A length mismatch is a whole-file error: exit 2, no OUT.
  const std::string short_index = scratch.write("short.npy", npy_file("<i8", "(5,)", indices.substr(0, 40)));
  fs::remove(out);
  const Outcome refused = run_bezinv(scratch, invert(points, out, "--curve-index '" + short_index + "'"));
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("short.npy: header: shape (5,) does not match the 6 points"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(CliNpy, CsvInNpyOutAndNpyInCsvOutAgree) {
  std::string csv = "curve,x,y\n";
  for (double t : params) {
    const Vec2 p = de_casteljau(kCubic, t);
    csv += "cubic," + csv_number(p[0]) + "," + csv_number(p[1]) + "\n";
  }
  csv += "cubic,nan,1\n";
  const std::string points_csv = scratch.write("points.csv", csv);
  const std::string out_npy = scratch.path("out.npy");
  ASSERT_EQ(run_bezinv(scratch, invert(points_csv, out_npy, "--chunk-points 4")).exit_code, 0);
  std::string dict;
  const std::vector<Record> from_csv = read_results_npy(read_file(out_npy), &dict);
  // The row count was not known up front: the header was rewritten at the end.
  EXPECT_NE(dict.find("'shape': (" + std::to_string(params.size() + 1) + ",)"), std::string::npos) << dict;
  ASSERT_EQ(from_csv.size(), params.size() + 1);
  EXPECT_EQ(from_csv.back().status, 4);  // invalid_input
  EXPECT_EQ(from_csv.back().path, 0);    // none

  const std::string out_csv = scratch.path("out.csv");
  ASSERT_EQ(run_bezinv(scratch, invert(points_npy(), out_csv, "--curve 0")).exit_code, 0);
  const std::vector<std::string> lines = split(read_file(out_csv), '\n');
  ASSERT_EQ(lines.size(), params.size() + 2);
  for (std::size_t i = 0; i < params.size(); ++i) {
    const std::vector<std::string> fields = split(lines[i + 1], ',');
    // Same input numbers, so the same answers, bit for bit (shortest round-trip text).
    EXPECT_EQ(std::bit_cast<std::uint64_t>(std::strtod(fields[0].c_str(), nullptr)),
              std::bit_cast<std::uint64_t>(from_csv[i].t))
        << i;
    EXPECT_EQ(fields[1], "ok") << i;
  }
}

TEST_F(CliNpy, ChunkedCsvRunMatchesTheUnchunkedOne) {
  std::string csv = "curve,x,y\n";
  for (int i = 0; i < 23; ++i) {
    const double t = i / 22.0;
    const Vec2 p = de_casteljau(i % 3 ? kCubic : kLine, t);
    csv += std::string(i % 3 ? "cubic," : "line,") + csv_number(p[0]) + "," + csv_number(p[1]) + "\n";
    if (i % 5 == 0) csv += "nope,0,0\n";
  }
  const std::string points = scratch.write("points.csv", csv);
  ASSERT_EQ(run_bezinv(scratch, invert(points, scratch.path("whole.csv"))).exit_code, 0);
  ASSERT_EQ(run_bezinv(scratch, invert(points, scratch.path("chunks.csv"), "--chunk-points 3")).exit_code, 0);
  EXPECT_EQ(read_file(scratch.path("chunks.csv")), read_file(scratch.path("whole.csv")));
  EXPECT_EQ(split(read_file(scratch.path("whole.csv")), '\n').size(), 1 + 23 + 5 + 1u);
}

TEST_F(CliNpy, MidStreamFailureLeavesNoOutputNoTemporaryAndTheOldOutputAlone) {
  std::string csv = "curve,x,y\n";
  for (int i = 0; i < 30; ++i) csv += "line,1,0.5\n";
  csv += "line,1,0.5,9\n";  // line 32, after ten 3-point chunks were written
  const std::string points = scratch.write("points.csv", csv);
  scratch.write("old.npy", "previous run");
  for (const std::string name : {"out.csv", "out.npy", "old.npy"}) {
    const Outcome run = run_bezinv(scratch, invert(points, scratch.path(name), "--chunk-points 3"));
    EXPECT_EQ(run.exit_code, 2) << name;
    EXPECT_NE(run.err.find("points.csv:32: expected 3 fields"), std::string::npos) << run.err;
  }
  EXPECT_EQ(read_file(scratch.path("old.npy")), "previous run");
  EXPECT_EQ(directory_entries(), (std::vector<std::string>{"curves.json", "old.npy", "points.csv", "stderr.txt", "stdout.txt"}));
}

TEST_F(CliNpy, CurveOptionsAreRefusedForCsvAndRequiredForNpy) {
  const std::string csv = scratch.write("points.csv", "curve,x,y\ncubic,1,1\n");
  const std::string out = scratch.path("out.csv");
  Outcome run = run_bezinv(scratch, invert(csv, out, "--curve cubic"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("points.csv: --curve and --curve-index are for .npy points"), std::string::npos) << run.err;
  run = run_bezinv(scratch, invert(points_npy(), out));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--curve ID or --curve-index"), std::string::npos) << run.err;
  run = run_bezinv(scratch, invert(points_npy(), out, "--curve nope"));
  EXPECT_EQ(run.exit_code, 2);
  run = run_bezinv(scratch, invert(points_npy(), out, "--curve cubic --curve-index x.npy"));
  EXPECT_NE(run.exit_code, 0);  // CLI11: the options exclude each other
  run = run_bezinv(scratch, invert(points_npy(), out, "--curve cubic --chunk-points 0"));
  EXPECT_NE(run.exit_code, 0);
  EXPECT_FALSE(fs::exists(out));
  const std::string f4 = scratch.write("f4.npy", npy_file("<f4", "(1, 2)", std::string(8, '\0')));
  run = run_bezinv(scratch, invert(f4, out, "--curve cubic"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("f4.npy: header: dtype '<f4' is not '<f8'"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
