#pragma once
// `bezinv stress`: how far each answer is from the truth, family by family (datasets/stress.hpp).
#include <string>
#include <vector>

#include "bezinv/curve.hpp"
#include "baselines.hpp"
#include "bezinv/datasets/stress.hpp"

namespace bezinv::cli {

// Which way the engine is asked: as by default, every point by the SVD, without refinement, with
// the inversion formula's algebraic step (--algebraic formula), or with off-curve rows by projection
// (--off-curve projection: their t is not the nearest point's, so only their status is compared).
enum class StressPath { default_path, svd_only, no_refine, formula, projection };
const char* to_string(StressPath path);

struct StressOptions {
  std::vector<datasets::Family> families{datasets::kFamilies.begin(), datasets::kFamilies.end()};
  std::vector<CurveKind> kinds{CurveKind::bezier, CurveKind::rational_bezier, CurveKind::rational};
  int min_degree = 1, max_degree = 24;
  std::size_t points = 100'000;  // in all, spread evenly over the cells (at least one per curve)
  int curves = 4;                // per family, kind and degree
  unsigned long long seed = 20261203;
  int threads = 0;
  std::vector<StressPath> paths{StressPath::default_path};
  double relative_tolerance = kDefaultRelativeTolerance;
  bool json = false;
  std::vector<baselines::Library> baselines;  // --baseline occt,sisl (when this build has them)
  std::string report_directory;  // --report DIR: the page, summary.json, reproducers (stress_report.hpp)
};

// Parses "a,b,c" lists and "lo-hi" degree ranges for the command line; throws std::invalid_argument
// naming the bad item.
std::vector<datasets::Family> parse_families(const std::string& list);
// Every family, comma-separated: the default of --families.
std::string all_families();
std::vector<CurveKind> parse_kinds(const std::string& list);
std::vector<StressPath> parse_paths(const std::string& list);
std::pair<int, int> parse_degrees(const std::string& range);
// "occt,sisl": each must be in this build (and SISL needs a large stack); throws
// std::invalid_argument saying what to do otherwise.
std::vector<baselines::Library> parse_baselines(const std::string& list);

// The run's JSON object (what --json prints), for callers that are not the command (the Python
// module's bezinv.stress); options.json and report_directory are not used.
std::string stress_json(const StressOptions& options);

// Prints the table (or one JSON object). Returns 0 when every status was right and every t there,
// 1 otherwise, 2 when the --report directory cannot be written (the message names what).
int run_stress(const StressOptions& options);

}  // namespace bezinv::cli
