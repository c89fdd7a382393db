// Past one machine: `bezinv invert --rows A:B` inverts a range of a .npy's rows, and `bezinv merge`
// joins the parts into the OUT of one run after checking every row is there once, in order. The
// reference is one run over the whole file: the merged OUT.npy must be the same bytes, and each
// part the same records as its rows of it.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <random>
#include <string>

#include "support/npy_bytes.hpp"
#include "support/run_bezinv.hpp"
#include "support/scratch_directory.hpp"

namespace {

using bezinv::test_support::append_le;
using bezinv::test_support::npy_bytes;
using bezinv::test_support::npy_dict;
using bezinv::test_support::read_file;
using bezinv::test_support::run_bezinv;
using bezinv::test_support::ScratchDirectory;

// (bezinv::test_support::quoted by its own name: for a non-const std::string, std::quoted, found by
// argument-dependent lookup, would be the better match.)
std::string shard_quoted(const std::string& path) { return bezinv::test_support::quoted(path); }

constexpr int kShardPoints = 1000;
constexpr std::size_t kRecord = 42;  // OUT.npy: five '<f8' and two '|u1'

struct ShardFiles {
  ScratchDirectory scratch{"bezinv-shard-"};
  std::string curves, points, index, invert;
  ShardFiles() {
    curves = scratch.write("curves.json", R"({"curves": [
      {"id": "a", "kind": "bezier", "points": [[0,0],[1,2],[2,-1],[3,1]]},
      {"id": "b", "kind": "rational_bezier", "points": [[0,0],[1,1],[2,0]], "weights": [1,2,1]}]})");
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> x(0.0, 3.0), y(-1.0, 2.0);
    std::string data, indices;
    for (int i = 0; i < kShardPoints; ++i) {
      append_le(data, x(rng));
      append_le(data, y(rng));
      append_le(indices, static_cast<std::int64_t>(rng() % 2));
    }
    points = scratch.write("points.npy", npy_bytes(npy_dict("'<f8'", "(1000, 2)"), data));
    index = scratch.write("index.npy", npy_bytes(npy_dict("'<i8'", "(1000,)"), indices));
    invert = "invert --curves " + shard_quoted(curves) + " --points " + shard_quoted(points) + " --curve-index " + shard_quoted(index);
  }
  std::string path(const std::string& name) const { return scratch.path(name); }
};

// The records after the header (a .npy of version 1.0: its header length at bytes 8-9).
std::string shard_records(const std::string& npy) {
  const std::size_t header = 10 + static_cast<unsigned char>(npy[8]) + 256 * static_cast<unsigned char>(npy[9]);
  return npy.substr(header);
}

TEST(CliShard, PartsOfRowRangesMergeIntoTheOneRunsBytes) {
  ShardFiles f;
  ASSERT_EQ(run_bezinv(f.scratch, f.invert + " --out " + shard_quoted(f.path("full.npy"))).exit_code, 0);
  const std::string full = read_file(f.path("full.npy"));
  ASSERT_EQ(shard_records(full).size(), kShardPoints * kRecord);
  // Three parts, the last past the end (a shard size that does not divide the rows).
  const std::pair<int, int> ranges[] = {{0, 300}, {300, 700}, {700, 1200}};
  std::string parts;
  for (const auto& [a, b] : ranges) {
    const std::string part = f.path("part-" + std::to_string(a) + ".npy");
    const auto run = run_bezinv(f.scratch, f.invert + " --rows " + std::to_string(a) + ":" + std::to_string(b) +
                                               " --out " + shard_quoted(part));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const std::size_t rows = std::min(b, kShardPoints) - a;
    EXPECT_EQ(shard_records(read_file(part)), shard_records(full).substr(a * kRecord, rows * kRecord)) << a << ":" << b;
    parts = shard_quoted(std::to_string(a) + ":" + std::to_string(b) + "=" + part) + " " + parts;  // any order
  }
  const auto merged = run_bezinv(f.scratch, "merge --points " + shard_quoted(f.points) + " --out " +
                                                shard_quoted(f.path("merged.npy")) + " " + parts);
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_EQ(read_file(f.path("merged.npy")), full);
}

// A gap, an overlap, a part of the wrong length, a range past the points, --rows on a CSV: each
// refused with the part or the option named, and no OUT written.
TEST(CliShard, MergeRefusesAGapAnOverlapOrAWrongPart) {
  ShardFiles f;
  for (const char* range : {"0:500", "500:1000"})
    ASSERT_EQ(run_bezinv(f.scratch, f.invert + " --rows " + range + " --out " +
                                        shard_quoted(f.path(std::string("p") + range[0] + ".npy")))
                  .exit_code,
              0);
  const std::string p0 = f.path("p0.npy"), p5 = f.path("p5.npy"), out = f.path("out.npy");
  auto merge = [&](const std::string& parts) {
    return run_bezinv(f.scratch, "merge --total 1000 --out " + shard_quoted(out) + " " + parts);
  };
  auto refused = [&](const bezinv::test_support::Outcome& run, const std::string& text) {
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_NE(run.err.find(text), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  };
  refused(merge(shard_quoted("0:500=" + p0)), "rows 500 to 1000 are in no part");
  refused(merge(shard_quoted("0:500=" + p0) + " " + shard_quoted("600:1000=" + p5)), "rows 500 to 600 are in no part");
  refused(merge(shard_quoted("0:500=" + p0) + " " + shard_quoted("400:1000=" + p5)), "overlaps the part before it");
  refused(merge(shard_quoted("0:400=" + p0) + " " + shard_quoted("400:1000=" + p5)), "500 rows, but --rows 0:400");
  refused(merge(shard_quoted("0-500=" + p0)), "expected A:B=PATH");
  refused(run_bezinv(f.scratch, f.invert + " --rows 2000:3000 --out " + shard_quoted(out)), "--rows 2000:3000: the file has 1000 points");
  const std::string csv = f.scratch.write("points.csv", "curve,x,y\na,0,0\n");
  refused(run_bezinv(f.scratch, "invert --curves " + shard_quoted(f.curves) + " --points " + shard_quoted(csv) +
                                    " --rows 0:1 --out " + shard_quoted(out)),
          "--rows is for .npy points");
}

}  // namespace
