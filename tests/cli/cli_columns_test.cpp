// `bezinv invert --columns point`: x_t, y_t, z_t after the other columns, P(t) on the row's curve,
// checked against de Casteljau here (not the engine's evaluation); the other columns the bytes of
// a run without it; in CSV and .npy; kept by `bezinv merge`, which refuses parts that differ.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "support/de_casteljau.hpp"
#include "support/npy_bytes.hpp"
#include "support/run_bezinv.hpp"
#include "support/scratch_directory.hpp"
#include "support/split.hpp"

namespace {

using bezinv::test_support::csv_number;
using bezinv::test_support::de_casteljau;
using bezinv::test_support::rational_de_casteljau;
using bezinv::test_support::read_file;
using bezinv::test_support::run_bezinv;
using bezinv::test_support::ScratchDirectory;
using bezinv::test_support::split;
using bezinv::test_support::Vec2;

std::string columns_quoted(const std::string& path) { return bezinv::test_support::quoted(path); }

const std::vector<Vec2> kColumnsCubic{{0, 0}, {1, 2}, {2, -1}, {3, 1}};
const std::vector<Vec2> kColumnsConic{{0, 0}, {1, 1}, {2, 0}};
const std::vector<double> kColumnsConicWeights{1, 2, 1};
const std::vector<std::array<double, 3>> kColumnsHelix{{1, 0, 0}, {1, 1, 0.5}, {-1, 1, 1}, {-1, 0, 1.5}};

std::array<double, 3> columns_helix_at(double t) {
  std::vector<std::array<double, 3>> p = kColumnsHelix;
  for (std::size_t level = 1; level < p.size(); ++level)
    for (std::size_t i = 0; i + level < p.size(); ++i)
      for (int c = 0; c < 3; ++c) p[i][c] = (1 - t) * p[i][c] + t * p[i + 1][c];
  return p[0];
}

// P(t) of the test's own evaluation, by the row's curve name.
std::array<double, 3> columns_expected_point(const std::string& curve, double t) {
  if (curve == "s") return columns_helix_at(t);
  const Vec2 p = curve == "a" ? de_casteljau(kColumnsCubic, t) : rational_de_casteljau(kColumnsConic, kColumnsConicWeights, t);
  return {p[0], p[1], 0.0};
}

struct ColumnsFiles {
  ScratchDirectory scratch{"bezinv-columns-"};
  std::string curves, points;
  std::vector<std::string> row_curves;  // each row's curve
  ColumnsFiles() {
    curves = scratch.write("curves.json", R"({"curves": [
      {"id": "a", "kind": "bezier", "points": [[0,0],[1,2],[2,-1],[3,1]]},
      {"id": "b", "kind": "rational_bezier", "points": [[0,0],[1,1],[2,0]], "weights": [1,2,1]},
      {"id": "s", "kind": "bezier", "points": [[1,0,0],[1,1,0.5],[-1,1,1],[-1,0,1.5]]}]})");
    std::string csv = "curve,x,y,z\n";
    auto row = [&](const std::string& curve, double x, double y, double z) {
      csv += curve + "," + csv_number(x) + "," + csv_number(y) + "," + (curve == "s" ? csv_number(z) : "") + "\n";
      row_curves.push_back(curve);
    };
    for (const double t : {0.0, 0.13, 0.5, 0.77, 1.0, 1.2, -0.1}) {
      const auto a = columns_expected_point("a", t), b = columns_expected_point("b", t), s = columns_expected_point("s", t);
      row("a", a[0], a[1], 0);
      row("b", b[0], b[1], 0);
      row("s", s[0], s[1], s[2]);
      row("a", a[0] + 0.05, a[1] - 0.03, 0);  // off the curve: P(t) is its nearest point
    }
    row("nowhere", 1, 1, 0);  // invalid_input: t nan
    row("a", 5, 1e308, 0);    // far off: off_curve, t of the nearest point
    points = scratch.write("points.csv", csv);
  }
  std::string invert(const std::string& out, const std::string& extra = "") const {
    return "invert --curves " + columns_quoted(curves) + " --points " + columns_quoted(points) + " --out " +
           columns_quoted(out) + extra;
  }
  // OUT without and with --columns point (extension `ext`): the two files' contents.
  std::pair<std::string, std::string> plain_and_with(const std::string& ext) const {
    const std::string plain = scratch.path("plain" + ext), with = scratch.path("with" + ext);
    EXPECT_EQ(run_bezinv(scratch, invert(plain)).exit_code, 0);
    const auto run = run_bezinv(scratch, invert(with, " --columns point"));
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return {read_file(plain), read_file(with)};
  }
};

double columns_number(const std::string& text) { return text == "nan" ? NAN : std::stod(text); }

TEST(CliColumns, PointColumnsInCsvAreTheCurvesPointAtT) {
  ColumnsFiles f;
  const auto [plain, with] = f.plain_and_with(".csv");
  ASSERT_FALSE(HasFailure());
  const std::vector<std::string> plain_lines = split(plain, '\n'), lines = split(with, '\n');
  ASSERT_EQ(lines.size(), plain_lines.size());
  EXPECT_EQ(lines[0], "t,status,residual,t2,sigma_min,sigma_next,path,reason,x_t,y_t,z_t");
  int checked = 0, nan_rows = 0;
  for (std::size_t i = 1; i + 1 < lines.size(); ++i) {
    const std::vector<std::string> fields = split(lines[i], ',');
    ASSERT_EQ(fields.size(), 11u) << lines[i];
    // The other columns: the bytes of the run without the point columns.
    EXPECT_EQ(lines[i].substr(0, plain_lines[i].size()), plain_lines[i]);
    const double t = columns_number(fields[0]);
    const double x = columns_number(fields[8]), y = columns_number(fields[9]), z = columns_number(fields[10]);
    if (std::isnan(t)) {
      EXPECT_TRUE(std::isnan(x) && std::isnan(y) && std::isnan(z)) << lines[i];
      ++nan_rows;
      continue;
    }
    const auto p = columns_expected_point(f.row_curves[i - 1], t);
    EXPECT_NEAR(x, p[0], 1e-14 * (1 + std::abs(p[0]))) << lines[i];
    EXPECT_NEAR(y, p[1], 1e-14 * (1 + std::abs(p[1]))) << lines[i];
    EXPECT_NEAR(z, p[2], 1e-14 * (1 + std::abs(p[2]))) << lines[i];
    ++checked;
  }
  EXPECT_EQ(checked, 29);  // the far row too: off_curve at its nearest point
  EXPECT_EQ(nan_rows, 1);  // the unknown curve
}

// The records after a .npy's header (version 1.0: its header length at bytes 8-9).
std::string columns_records(const std::string& npy) {
  const std::size_t header = 10 + static_cast<unsigned char>(npy[8]) + 256 * static_cast<unsigned char>(npy[9]);
  return npy.substr(header);
}

TEST(CliColumns, PointColumnsInNpyFollowTheRecordsFields) {
  ColumnsFiles f;
  const auto [plain, npy] = f.plain_and_with(".npy");
  ASSERT_FALSE(HasFailure());
  EXPECT_NE(npy.find("('path', '|u1'), ('x_t', '<f8'), ('y_t', '<f8'), ('z_t', '<f8')]"), std::string::npos);
  const std::string records = columns_records(npy), plain_records = columns_records(plain);
  const std::size_t rows = f.row_curves.size();
  ASSERT_EQ(plain_records.size(), rows * 42);
  ASSERT_EQ(records.size(), rows * 66);
  for (std::size_t i = 0; i < rows; ++i) {
    EXPECT_EQ(records.substr(i * 66, 42), plain_records.substr(i * 42, 42)) << i;
    double t, xyz[3];
    std::memcpy(&t, records.data() + i * 66, 8);
    std::memcpy(xyz, records.data() + i * 66 + 42, 24);
    if (std::isnan(t)) {
      EXPECT_TRUE(std::isnan(xyz[0]) && std::isnan(xyz[1]) && std::isnan(xyz[2])) << i;
      continue;
    }
    const auto p = columns_expected_point(f.row_curves[i], t);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(xyz[c], p[c], 1e-14 * (1 + std::abs(p[c]))) << i;
  }
}

TEST(CliColumns, MergeKeepsThePointColumnsAndRefusesPartsWithout) {
  ScratchDirectory scratch{"bezinv-columns-merge-"};
  const std::string curves = scratch.write("curves.json", R"({"curves": [{"id": "a", "kind": "bezier", "points": [[0,0],[1,2],[2,-1],[3,1]]}]})");
  std::string data;
  for (int i = 0; i < 100; ++i) {
    const Vec2 p = de_casteljau(kColumnsCubic, i / 99.0);
    bezinv::test_support::append_le(data, p[0]);
    bezinv::test_support::append_le(data, p[1] + (i % 3 == 0 ? 0.01 : 0.0));
  }
  const std::string points = scratch.write("points.npy", bezinv::test_support::npy_bytes(bezinv::test_support::npy_dict("'<f8'", "(100, 2)"), data));
  const std::string invert = "invert --curves " + columns_quoted(curves) + " --points " + columns_quoted(points) + " --curve a";
  ASSERT_EQ(run_bezinv(scratch, invert + " --columns point --out " + columns_quoted(scratch.path("full.npy"))).exit_code, 0);
  ASSERT_EQ(run_bezinv(scratch, invert + " --columns point --rows 0:40 --out " + columns_quoted(scratch.path("p0.npy"))).exit_code, 0);
  ASSERT_EQ(run_bezinv(scratch, invert + " --columns point --rows 40:100 --out " + columns_quoted(scratch.path("p1.npy"))).exit_code, 0);
  ASSERT_EQ(run_bezinv(scratch, invert + " --rows 40:100 --out " + columns_quoted(scratch.path("q1.npy"))).exit_code, 0);
  const auto merged = run_bezinv(scratch, "merge --points " + columns_quoted(points) + " --out " +
                                              columns_quoted(scratch.path("merged.npy")) + " " +
                                              columns_quoted("0:40=" + scratch.path("p0.npy")) + " " +
                                              columns_quoted("40:100=" + scratch.path("p1.npy")));
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_EQ(read_file(scratch.path("merged.npy")), read_file(scratch.path("full.npy")));
  const auto mixed = run_bezinv(scratch, "merge --points " + columns_quoted(points) + " --out " +
                                             columns_quoted(scratch.path("mixed.npy")) + " " +
                                             columns_quoted("0:40=" + scratch.path("p0.npy")) + " " +
                                             columns_quoted("40:100=" + scratch.path("q1.npy")));
  EXPECT_NE(mixed.exit_code, 0);
  EXPECT_NE(mixed.err.find("q1.npy: has no point columns"), std::string::npos) << mixed.err;
  EXPECT_FALSE(std::filesystem::exists(scratch.path("mixed.npy")));
}

TEST(CliColumns, AnUnknownColumnIsAnError) {
  ColumnsFiles f;
  const auto run = run_bezinv(f.scratch, f.invert(f.scratch.path("out.csv"), " --columns point,normal"));
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("normal"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(f.scratch.path("out.csv")));
}

}  // namespace
