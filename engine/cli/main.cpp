// The `bezinv` command: argument parsing, then the data flow of README "How it works":
// CURVES.json -> curves -> plans, POINTS.csv -> points, invert, OUT.csv.
#include <array>
#include <chrono>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <span>
#include <string>
#include <system_error>
#include <vector>

#include <CLI/CLI.hpp>

#include "bezinv/curve.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/io.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/tolerances.hpp"
#include "demo.hpp"

// The project version from CMake when the build passes it; otherwise the one in CMakeLists.txt.
#ifndef BEZINV_VERSION
#define BEZINV_VERSION "0.1.0"
#endif

namespace {

// Exit codes: 0 done (OUT written, whatever the per-point statuses), 2 an input file cannot be used
// (nothing written), 1 anything unexpected. CLI11 uses its own codes (>= 100) for bad arguments.
constexpr int kExitInputError = 2;
constexpr int kExitInternalError = 1;

struct InvertArguments {
  std::string curves_path, points_path, out_path;
  double relative_tolerance = bezinv::kDefaultRelativeTolerance;
  bool no_refine = false;
  int threads = 0;
  bool verbose = false;
};

// Fail before reading anything when OUT cannot be placed: a missing directory would otherwise only
// show up after all points were inverted. (write_results_csv reports every other failure.)
void check_output_directory(const std::string& out_path) {
  const std::filesystem::path directory = std::filesystem::path(out_path).parent_path();
  std::error_code error;
  if (!directory.empty() && !std::filesystem::is_directory(directory, error))
    throw bezinv::InputError(out_path + ": cannot write: directory " + directory.string() + " does not exist");
}

void print_summary(const InvertArguments& arguments, std::span<const bezinv::PointResult> results,
                   double seconds) {
  using bezinv::Status;
  constexpr std::array statuses{Status::ok,        Status::outside_segment, Status::double_point,
                                Status::off_curve, Status::invalid_input,   Status::failed};
  std::array<std::size_t, statuses.size()> counts{};
  for (const auto& result : results)
    for (std::size_t s = 0; s < statuses.size(); ++s) counts[s] += result.status == statuses[s];
  std::string line = "bezinv: " + std::to_string(results.size()) + " points in " + std::to_string(seconds) + " s:";
  for (std::size_t s = 0; s < statuses.size(); ++s)
    line += std::string(" ") + to_string(statuses[s]) + " " + std::to_string(counts[s]);
  std::fprintf(stderr, "%s -> %s\n", line.c_str(), arguments.out_path.c_str());
}

int run_invert(const InvertArguments& arguments) {
  const auto start = std::chrono::steady_clock::now();
  check_output_directory(arguments.out_path);

  const std::vector<bezinv::Curve> curves = bezinv::read_curves_json(arguments.curves_path);
  std::vector<bezinv::InversionPlan> plans;
  plans.reserve(curves.size());
  for (std::size_t i = 0; i < curves.size(); ++i) {
    try {
      plans.push_back(bezinv::make_plan(curves[i]));
    } catch (const bezinv::CurveError& e) {
      // read_curves_json already validated the curve; name it anyway should the plan refuse it.
      throw bezinv::InputError(arguments.curves_path + ": curves[" + std::to_string(i) + "] (id \"" + curves[i].id +
                               "\"): " + e.what());
    }
  }

  const std::vector<bezinv::PointRow> rows = bezinv::read_points_csv(arguments.points_path, curves);
  std::vector<int> curve_of(rows.size());
  std::vector<bezinv::Point> points(rows.size());
  std::vector<bezinv::PointResult> results(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    curve_of[i] = rows[i].curve;
    points[i] = rows[i].point;
    if (rows[i].curve < 0) {
      // invert() leaves rows with a negative curve as set here.
      results[i].status = bezinv::Status::invalid_input;
      results[i].reason = rows[i].reason;
    }
  }

  bezinv::InvertOptions options;
  options.relative_tolerance = arguments.relative_tolerance;
  options.refine = !arguments.no_refine;
  options.threads = arguments.threads;
  bezinv::invert(plans, curve_of, points, results, options);

  bezinv::write_results_csv(arguments.out_path, results);

  if (arguments.verbose) {
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    print_summary(arguments, results, elapsed.count());
  }
  return 0;
}

// --tol: a relative tolerance has to be a finite positive number (CLI11's PositiveNumber lets
// "inf" and "nan" through). CLI11 puts the option name in front of the message.
std::string check_relative_tolerance(std::string& text) {
  double value = 0.0;
  const char* const end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc() || stop != end) return "'" + text + "' is not a number";
  if (!std::isfinite(value) || value <= 0.0) return "must be finite and > 0, got " + text;
  return {};
}

// --threads, --points: CLI11's NonNegativeNumber would print its upper bound, DBL_MAX in full.
std::string check_count(std::string& text, long long minimum) {
  long long value = 0;
  const char* const end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc() || stop != end || value < minimum)
    return "must be an integer >= " + std::to_string(minimum) + ", got '" + text + "'";
  return {};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bezinv: finds the parameter t of points on plane rational Bezier curves\n"
               "(Bernstein-Bezout matrix and SVD, Marco & Martinez).",
               "bezinv"};
  app.set_version_flag("--version", std::string("bezinv ") + BEZINV_VERSION);
  app.require_subcommand(0, 1);

  InvertArguments invert_arguments;
  CLI::App* invert = app.add_subcommand("invert", "Invert every point of POINTS.csv on its curve, write OUT.csv");
  invert->add_option("--curves", invert_arguments.curves_path, "Curves file (JSON)")->required();
  invert->add_option("--points", invert_arguments.points_path, "Points file (CSV: curve,x,y)")->required();
  invert->add_option("--out", invert_arguments.out_path, "Results file (CSV), one row per point, in order")
      ->required();
  invert
      ->add_option("--tol", invert_arguments.relative_tolerance,
                   "On-curve tolerance relative to the control-point bounding-box diagonal")
      ->check(CLI::Validator(check_relative_tolerance, "REL>0"))
      ->capture_default_str();
  invert->add_flag("--no-refine", invert_arguments.no_refine,
                   "Report the paper's algebraic t (no Newton refinement to the nearest point)");
  const CLI::Validator non_negative([](std::string& text) { return check_count(text, 0); }, "N>=0");
  const CLI::Validator positive([](std::string& text) { return check_count(text, 1); }, "N>=1");
  invert->add_option("--threads", invert_arguments.threads, "Worker threads (0: all cores)")
      ->check(non_negative)
      ->capture_default_str();
  invert->add_flag("--verbose,-v", invert_arguments.verbose, "One-line summary on stderr");

  std::size_t demo_points = 1000000;
  int demo_threads = 0;
  CLI::App* demo = app.add_subcommand("demo", "Invert generated points with known parameters; report speed and accuracy");
  demo->add_option("--points", demo_points, "Number of points")->check(positive)->capture_default_str();
  demo->add_option("--threads", demo_threads, "Worker threads (0: all cores)")
      ->check(non_negative)
      ->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  try {
    if (invert->parsed()) return run_invert(invert_arguments);
    if (demo->parsed()) return bezinv::cli::run_demo(demo_points, demo_threads);
  } catch (const bezinv::InputError& e) {
    std::fprintf(stderr, "bezinv: %s\n", e.what());
    return kExitInputError;
  } catch (const bezinv::CurveError& e) {
    std::fprintf(stderr, "bezinv: %s\n", e.what());
    return kExitInputError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bezinv: internal error: %s\n", e.what());
    return kExitInternalError;
  }

  // No subcommand: there is nothing sensible to do by default.
  std::fputs(app.help().c_str(), stderr);
  return kExitInputError;
}
