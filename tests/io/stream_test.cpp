// invert_stream from the curves (engine/io/stream.cpp): plans are built for the curves the
// points name, and the rows are those of the plans built up front.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "bezinv/io.hpp"
#include "plan_data.hpp"
#include "bezinv/plan.hpp"
#include "support/scratch_directory.hpp"

namespace bezinv {
namespace {

using test_support::read_file;
using test_support::ScratchDirectory;

// `count` random cubics c0, c1, ... as CURVES.json.
std::string curves_json(int count, int degree) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> coordinate(0.0, 1.0);
  std::string json = "{\"curves\": [";
  for (int i = 0; i < count; ++i) {
    json += std::string(i ? "," : "") + "{\"id\": \"c" + std::to_string(i) + "\", \"kind\": \"bezier\", \"points\": [";
    for (int k = 0; k <= degree; ++k)
      json += std::string(k ? "," : "") + "[" + std::to_string(coordinate(rng)) + "," + std::to_string(coordinate(rng)) + "]";
    json += "]}";
  }
  return json + "]}";
}

TEST(InvertStreamFromCurves, BuildsOnlyThePlansThePointsName) {
  ScratchDirectory scratch{"bezinv-stream-curves-"};
  const std::vector<Curve> curves = read_curves_json(scratch.write("curves.json", curves_json(500, 5)));
  // Points of curves 7, 499 and 7 again, an unknown id, and curve 123 by index, over several chunks.
  std::string csv = "curve,x,y\n";
  const std::vector<std::string> names = {"c7", "c499", "c7", "nope", "123"};
  std::vector<int> index = {7, 499, 7, -1, 123};
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto p = index[i] >= 0 ? curves[static_cast<std::size_t>(index[i])].point(0.25 + 0.1 * static_cast<double>(i))
                                 : std::array<double, 2>{0.0, 0.0};
    csv += names[i] + "," + std::to_string(p[0]) + "," + std::to_string(p[1]) + "\n";
  }
  const std::string points = scratch.write("points.csv", csv);

  for (std::size_t chunk : {1, 2, 100}) {
    const auto reader = open_points(points, curves);
    const auto writer = open_results(scratch.path("lazy.csv"), 1);
    const StreamSummary summary = invert_stream(*reader, *writer, std::span<const Curve>(curves), {}, chunk);
    writer->commit();
    EXPECT_EQ(summary.points, names.size()) << chunk;
    EXPECT_EQ(summary.plans_built, 3u) << chunk;  // c7, c499, c123; nothing for the unknown id

    // The same rows as with every plan built first.
    const std::vector<InversionPlan> plans = make_plans(curves);
    const auto reader_all = open_points(points, curves);
    const auto writer_all = open_results(scratch.path("all.csv"), 1);
    invert_stream(*reader_all, *writer_all, plans, {}, chunk);
    writer_all->commit();
    EXPECT_EQ(read_file(scratch.path("lazy.csv")), read_file(scratch.path("all.csv"))) << chunk;
  }
}

TEST(MakePlansOfIndices, BuildsTheNamedPlansAndLeavesTheOthers) {
  ScratchDirectory scratch{"bezinv-plans-indices-"};
  const std::vector<Curve> curves = read_curves_json(scratch.write("curves.json", curves_json(40, 7)));
  std::vector<InversionPlan> plans(curves.size());
  const std::vector<std::size_t> indices = {3, 39, 0, 17};
  make_plans(curves, indices, plans, 2);
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const bool named = std::find(indices.begin(), indices.end(), i) != indices.end();
    EXPECT_EQ(plans[i].degree(), named ? 7 : 0) << i;
    if (named) {
      EXPECT_EQ(plans[i].curve().id, curves[i].id);
      EXPECT_EQ(bezinv::detail::plan_data(plans[i]).B0, bezinv::detail::plan_data(make_plan(curves[i])).B0) << i;
    }
  }
}

}  // namespace
}  // namespace bezinv
