// The `bezinv` command: argument parsing, then the data flow of docs/README.md:
// CURVES.json -> curves -> plans, then POINTS (.csv/.npy) -> invert -> OUT (.csv/.npy) a chunk at a time.
#include <algorithm>
#include <array>
#include <chrono>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <system_error>
#include <tuple>
#include <utility>
#include <vector>

#include <sys/stat.h>  // stat: OUT compared with the inputs by device and inode
#include <unistd.h>    // isatty: the progress line is for a person at a terminal only

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include "bezinv/curve.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/io.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/tolerances.hpp"
#include "convert.hpp"
#include "merge.hpp"
#include "demo.hpp"
#include "formula.hpp"
#include "profile.hpp"
#include "stress.hpp"

// The project version from CMake when the build passes it; otherwise the one in CMakeLists.txt.
#ifndef BEZINV_VERSION
#define BEZINV_VERSION "0.1.0"
#endif

namespace {

// Exit codes: 0 done (OUT written, whatever the per-point statuses), 2 an input file cannot be used
// (nothing written), 1 anything unexpected. CLI11 uses its own codes (>= 100) for bad arguments.
constexpr int kExitInputError = 2;
constexpr int kExitInternalError = 1;

// --threads above this is refused: far past any core count it only costs memory, and TBB fails
// outright on absurd counts.
constexpr long long kMaxThreads = 1024;
// --chunk-points above this is refused: about 100 bytes a point, so 1.7 GB of buffers in flight.
constexpr std::size_t kMaxChunkPoints = std::size_t{1} << 24;

// The names bezinv::algebraic_named reads, for --algebraic of invert and profile.
const std::vector<std::string> kAlgebraicNames{"auto", "bezout", "formula"};

struct InvertArguments {
  std::string curves_path, points_path, out_path;
  double relative_tolerance = bezinv::kDefaultRelativeTolerance;
  bool no_refine = false;
  bool svd_only = false;
  std::string algebraic = "auto";
  std::string off_curve = "nearest";
  int threads = 0;
  bool verbose = false;
  bezinv::CurveSelection selection;
  std::size_t chunk_points = bezinv::kDefaultChunkPoints;
  std::vector<std::string> columns;  // optional output columns: "point"
};

// One self-overwriting line on stderr: points done, how far through the input, rate. Only when
// stderr is a terminal (never in logs or pipes), only once the job has run a second, at most
// ten times a second; wiped again at the end so what follows starts on a clean line.
class ProgressLine {
 public:
  ProgressLine() : enabled_(::isatty(STDERR_FILENO) == 1), start_(std::chrono::steady_clock::now()) {}
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;
  ~ProgressLine() {
    if (drawn_) std::fputs("\r\033[K", stderr);
  }

  void update(const bezinv::ReadProgress& progress) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - start_).count();
    if (seconds < 1.0 || (drawn_ && now - last_ < std::chrono::milliseconds(100))) return;
    last_ = now;
    drawn_ = true;
    const double rate = static_cast<double>(progress.points) / seconds;
    char line[160];
    if (progress.points_total > 0) {
      std::snprintf(line, sizeof line, "\rbezinv: %llu / %llu points (%.0f%%), %.2f M points/s\033[K",
                    static_cast<unsigned long long>(progress.points),
                    static_cast<unsigned long long>(progress.points_total),
                    100.0 * static_cast<double>(progress.points) / static_cast<double>(progress.points_total), rate / 1e6);
    } else if (progress.bytes_total > 0) {
      std::snprintf(line, sizeof line, "\rbezinv: %llu points, %.0f%% of %.1f MB read, %.2f M points/s\033[K",
                    static_cast<unsigned long long>(progress.points),
                    100.0 * static_cast<double>(progress.bytes) / static_cast<double>(progress.bytes_total),
                    static_cast<double>(progress.bytes_total) / 1e6, rate / 1e6);
    } else {
      std::snprintf(line, sizeof line, "\rbezinv: %llu points, %.2f M points/s\033[K",
                    static_cast<unsigned long long>(progress.points), rate / 1e6);
    }
    std::fputs(line, stderr);
    std::fflush(stderr);
  }

 private:
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

// Fail before reading anything when OUT cannot be placed: a missing directory would otherwise only
// show up after all points were inverted. (write_results_csv reports every other failure.)
void check_output_directory(const std::string& out_path) {
  const std::filesystem::path directory = std::filesystem::path(out_path).parent_path();
  std::error_code error;
  if (!directory.empty() && !std::filesystem::is_directory(directory, error))
    throw bezinv::InputError(out_path + ": cannot write: directory " + directory.string() + " does not exist");
}

// Whether two paths name one file (device and inode; a character device never counts).
bool same_file(const std::string& a, const std::string& b) {
  struct stat first {}, second {};
  return ::stat(a.c_str(), &first) == 0 && ::stat(b.c_str(), &second) == 0 && !S_ISCHR(first.st_mode) &&
         first.st_dev == second.st_dev && first.st_ino == second.st_ino;
}

// OUT must not be an input under another name (./points.csv, a symbolic or hard link): the
// results would replace it. stat() follows links, and device + inode name the file whatever the
// spelling. A character device may be both (a terminal as --points /dev/stdin and --out /dev/stdout).
void check_output_is_not_an_input(const InvertArguments& arguments) {
  struct stat out {};
  if (::stat(arguments.out_path.c_str(), &out) != 0 || S_ISCHR(out.st_mode)) return;
  const std::pair<const char*, const std::string*> inputs[] = {{"--curves", &arguments.curves_path},
                                                                {"--points", &arguments.points_path},
                                                                {"--curve-index", &arguments.selection.index_path}};
  for (const auto& [option, path] : inputs) {
    struct stat input {};
    if (path->empty() || ::stat(path->c_str(), &input) != 0) continue;
    if (input.st_dev == out.st_dev && input.st_ino == out.st_ino)
      throw bezinv::InputError(arguments.out_path + ": --out is the same file as " + option + " " + *path +
                               "; refusing to overwrite an input");
  }
}

// --threads: bounded after parsing so that a count too large is an input error (exit 2) like the
// others, whatever its size.
int checked_threads(long long requested) {
  if (requested > kMaxThreads)
    throw bezinv::InputError("--threads " + std::to_string(requested) + ": at most " + std::to_string(kMaxThreads) +
                             " (0: all cores)");
  return static_cast<int>(requested);
}

void check_chunk_points(std::size_t chunk_points) {
  if (chunk_points > kMaxChunkPoints)
    throw bezinv::InputError("--chunk-points " + std::to_string(chunk_points) + ": at most " +
                             std::to_string(kMaxChunkPoints) + " (about 100 bytes of memory per point)");
}

// With an explicit thread count, TBB's limit is raised (or lowered) to it: every arena then gets
// the workers it asks for, and TBB prints no warning for counts above the core count.
class ParallelismLimit {
 public:
  explicit ParallelismLimit(int threads) {
    if (threads > 0) limit_.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  }
  // tbb::global_control copies, and each copy's destructor would lift the limit.
  ParallelismLimit(const ParallelismLimit&) = delete;
  ParallelismLimit& operator=(const ParallelismLimit&) = delete;

 private:
  std::optional<tbb::global_control> limit_;
};

void print_summary(const InvertArguments& arguments, const bezinv::StreamSummary& summary, double seconds) {
  using bezinv::Status;
  constexpr std::array statuses{Status::ok,        Status::outside_segment, Status::double_point,
                                Status::off_curve, Status::invalid_input,   Status::failed};
  std::string line = "bezinv: " + std::to_string(summary.points) + " points in " + std::to_string(seconds) + " s:";
  for (const Status status : statuses)
    line += std::string(" ") + to_string(status) + " " +
            std::to_string(summary.by_status[static_cast<std::size_t>(status)]);
  std::fprintf(stderr, "%s -> %s\n", line.c_str(), arguments.out_path.c_str());
}

int run_invert(const InvertArguments& arguments) {
  const auto start = std::chrono::steady_clock::now();
  check_output_directory(arguments.out_path);

  const std::vector<bezinv::Curve> curves = bezinv::read_curves_json(arguments.curves_path);

  bezinv::InvertOptions options;
  options.relative_tolerance = arguments.relative_tolerance;
  options.refine = !arguments.no_refine;
  options.fast_path = !arguments.svd_only;
  bezinv::algebraic_named(arguments.algebraic, options.algebraic);  // checked by the parser
  options.off_curve = arguments.off_curve == "projection" ? bezinv::OffCurve::projection : bezinv::OffCurve::nearest;
  options.threads = arguments.threads;

  const auto reader = bezinv::open_points(arguments.points_path, curves, arguments.selection);
  bezinv::ResultColumns columns;
  columns.point = std::find(arguments.columns.begin(), arguments.columns.end(), "point") != arguments.columns.end();
  const auto writer = bezinv::open_results(arguments.out_path, arguments.threads, columns);
  bezinv::StreamSummary summary;
  {
    ProgressLine progress;
    // Plans are built as the points need them (invert_stream).
    try {
      summary = bezinv::invert_stream(*reader, *writer, curves, options, arguments.chunk_points,
                                      [&](const bezinv::ReadProgress& p) { progress.update(p); });
    } catch (const bezinv::PlansError& e) {
      // read_curves_json already validated the curve; name it anyway should the plan refuse it
      // (the CurveError's text quotes the id, escaped).
      throw bezinv::InputError(arguments.curves_path + ": curves[" + std::to_string(e.index) + "]: " + e.what());
    }
    writer->commit();
  }

  if (arguments.verbose) {
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    print_summary(arguments, summary, elapsed.count());
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
  CLI::App* invert = app.add_subcommand("invert", "Invert every point of POINTS on its curve, write OUT");
  invert->add_option("--curves", invert_arguments.curves_path, "Curves file (JSON)")->required();
  invert
      ->add_option("--points", invert_arguments.points_path,
                   "Points file: CSV (curve,x,y) or .npy (float64, shape (N, 2))")
      ->required();
  invert
      ->add_option("--out", invert_arguments.out_path,
                   "Results file: CSV, or .npy (structured array), one row per point, in order")
      ->required();
  CLI::Option* curve = invert->add_option("--curve", invert_arguments.selection.curve,
                                          ".npy points: the curve (id or 0-based index) of every point");
  CLI::Option* curve_index =
      invert->add_option("--curve-index", invert_arguments.selection.index_path,
                         ".npy points: int32/int64 (N,) .npy of 0-based curve indices, one per point");
  curve->excludes(curve_index);
  invert
      ->add_option("--tol", invert_arguments.relative_tolerance,
                   "On-curve tolerance relative to the control-point bounding-box diagonal")
      ->check(CLI::Validator(check_relative_tolerance, "REL>0"))
      ->capture_default_str();
  invert->add_flag("--no-refine", invert_arguments.no_refine,
                   "Report the paper's algebraic t (no Newton refinement to the nearest point)");
  invert->add_flag("--svd-only", invert_arguments.svd_only,
                   "Answer every point by the SVD (exact sigma_min/sigma_next on every row; slower)");
  invert->add_option("--algebraic", invert_arguments.algebraic,
                     "The fast path's algebraic step: bezout (B's null vector), formula (the curve's inversion "
                     "formula N/M where it is valid, path formula; with --no-refine, N/M itself) or auto (formula "
                     "on conics and cubics of one denominator and moderate weights, on a curve close to a lower "
                     "degree, such as a smooth function's graph, and at degrees 4-20 on a curve with enough points "
                     "to repay making its formula, 10,000 at degree 4 to 541,000 at 20; bezout elsewhere)")
      ->check(CLI::IsMember(kAlgebraicNames))
      ->capture_default_str();
  std::string invert_rows;
  invert->add_option("--rows", invert_rows,
                     ".npy points: only rows A to B (0-based, B excluded; B past the end: to the end), for sharing "
                     "one file over machines (bezinv merge joins the parts)");
  invert->add_option("--columns", invert_arguments.columns,
                     "Optional output columns after the others: point (x_t,y_t,z_t: the curve's point at t; z_t 0 "
                     "for a plane curve, nan where t is nan)")
      ->delimiter(',')
      ->check(CLI::IsMember({"point"}));
  invert->add_option("--off-curve", invert_arguments.off_curve,
                     "An off_curve row's t: nearest (the nearest point of the segment) or projection (the "
                     "inversion formula's projection N/M of the point, path projection, where the formula is valid)")
      ->check(CLI::IsMember({"nearest", "projection"}))
      ->capture_default_str();
  const CLI::Validator non_negative([](std::string& text) { return check_count(text, 0); }, "N>=0");
  const CLI::Validator positive([](std::string& text) { return check_count(text, 1); }, "N>=1");
  const std::string threads_help = "Worker threads (0: all cores; at most " + std::to_string(kMaxThreads) + ")";
  long long invert_threads = 0;
  invert->add_option("--threads", invert_threads, threads_help)
      ->check(non_negative)
      ->capture_default_str();
  invert->add_flag("--verbose,-v", invert_arguments.verbose, "One-line summary on stderr");
  invert
      ->add_option("--chunk-points", invert_arguments.chunk_points,
                   "Points read, inverted and written at a time (memory ~100 bytes per point; at most " +
                       std::to_string(kMaxChunkPoints) + ")")
      ->check(positive)
      ->capture_default_str();

  std::size_t demo_points = 1000000;
  long long demo_threads = 0;
  CLI::App* demo = app.add_subcommand("demo", "Invert generated points with known parameters; report speed and accuracy");
  demo->add_option("--points", demo_points, "Number of points")->check(positive)->capture_default_str();
  demo->add_option("--threads", demo_threads, threads_help)
      ->check(non_negative)
      ->capture_default_str();

  bezinv::cli::ProfileOptions profile_options;
  std::string profile_kind = "rational_bezier";
  CLI::App* profile = app.add_subcommand(
      "profile", "Generate points on random curves, invert them in memory; report points/s per stage");
  profile->add_option("--kind", profile_kind, "Curve kind")
      ->check(CLI::IsMember({"bezier", "rational_bezier", "rational"}))
      ->capture_default_str();
  profile->add_option("--degree", profile_options.degree, "Curve degree")
      ->check(CLI::Range(1, bezinv::kMaxDegree))
      ->capture_default_str();
  profile->add_option("--points", profile_options.points, "Number of points")->check(positive)->capture_default_str();
  profile->add_option("--dim", profile_options.dimension, "2: plane curves; 3: space curves (lifted off their plane)")
      ->check(CLI::IsMember({2, 3}))
      ->capture_default_str();
  profile->add_option("--curves", profile_options.curves, "Distinct curves the points are spread over")
      ->check(positive)
      ->capture_default_str();
  long long profile_threads = 0;
  profile->add_option("--threads", profile_threads, threads_help)
      ->check(non_negative)
      ->capture_default_str();
  profile->add_option("--noise", profile_options.noise, "Move points off the curve by up to D x its diagonal")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  profile->add_flag("--mixed", profile_options.mixed,
                    "With --noise: leave every other point on the curve (batches holding both kinds)");
  bool profile_no_refine = false;
  profile->add_flag("--no-refine", profile_no_refine, "Algebraic t only (no Newton refinement)");
  bool profile_svd_only = false;
  profile->add_flag("--svd-only", profile_svd_only, "Every point by the SVD (no LU fast path)");
  std::string profile_algebraic = "auto";
  profile->add_option("--algebraic", profile_algebraic, "The fast path's algebraic step: auto, bezout or formula")
      ->check(CLI::IsMember(kAlgebraicNames))
      ->capture_default_str();
  std::string profile_off_curve = "nearest";
  profile->add_option("--off-curve", profile_off_curve, "An off_curve row's t: nearest or projection")
      ->check(CLI::IsMember({"nearest", "projection"}))
      ->capture_default_str();
  profile->add_flag("--json", profile_options.json, "One JSON object on stdout");

  bezinv::cli::StressOptions stress_options;
  std::string stress_families = bezinv::cli::all_families(),
              stress_kinds = "bezier,rational_bezier,rational", stress_degrees = "1-24", stress_paths = "default";
  long long stress_threads = 0;
  CLI::App* stress = app.add_subcommand(
      "stress", "Invert points of known answers family by family; report each answer's error against a "
                "high-precision truth, and every wrong status (exit 1 if any)");
  stress->add_option("--families", stress_families, "Comma-separated families (datasets_gen/include/bezinv/datasets/stress.hpp)")
      ->capture_default_str();
  stress->add_option("--kinds", stress_kinds, "Comma-separated curve kinds")->capture_default_str();
  stress->add_option("--degrees", stress_degrees, "Degree N or range LO-HI")->capture_default_str();
  stress->add_option("--points", stress_options.points, "Points in all, spread over the cells")
      ->check(positive)
      ->capture_default_str();
  stress->add_option("--curves", stress_options.curves, "Random curves per family, kind and degree")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  stress->add_option("--seed", stress_options.seed, "Random seed")->capture_default_str();
  stress->add_option("--threads", stress_threads, threads_help)->check(non_negative)->capture_default_str();
  stress->add_option("--paths", stress_paths, "Comma-separated: default,svd-only,no-refine,formula,projection")->capture_default_str();
  stress
      ->add_option("--tol", stress_options.relative_tolerance,
                   "On-curve tolerance relative to the control-point bounding-box diagonal")
      ->check(CLI::Validator(check_relative_tolerance, "REL>0"))
      ->capture_default_str();
  stress->add_flag("--json", stress_options.json, "One JSON object on stdout");
  std::string stress_baselines;
  stress->add_option("--baseline", stress_baselines,
                     "Comma-separated: occt,sisl, the same rows through OpenCASCADE and SISL (a build with them)");
  stress->add_option("--report", stress_options.report_directory,
                     "Write DIR/index.html (one page, no script), DIR/summary.json and reproducers in DIR/repro");

  std::string convert_curves, convert_out;
  CLI::App* convert = app.add_subcommand(
      "convert", "Write CURVES.json with every matrix-weighted curve as an ordinary rational Bezier curve");
  convert->add_option("--curves", convert_curves, "CURVES.json")->required();
  convert->add_option("--out", convert_out, "The converted CURVES.json")->required();

  std::string merge_out, merge_points;
  std::uint64_t merge_rows = 0;
  std::vector<std::string> merge_parts;
  CLI::App* merge = app.add_subcommand(
      "merge", "Join the OUT.npy parts of bezinv invert --rows runs into one OUT.npy, every row once and in order");
  merge->add_option("--out", merge_out, "The joined OUT.npy")->required();
  CLI::Option* merge_points_option =
      merge->add_option("--points", merge_points, "The POINTS.npy the parts were made from (its row count)");
  CLI::Option* merge_rows_option = merge->add_option("--total", merge_rows, "The row count, without --points");
  merge_points_option->excludes(merge_rows_option);
  merge->add_option("parts", merge_parts, "Each part as A:B=PART.npy, A:B its --rows range")->required();

  bezinv::cli::FormulaOptions formula_options;
  std::string formula_base;
  CLI::App* formula = app.add_subcommand(
      "formula", "Per curve: the inversion formula t = N(x,y)/M(x,y), its centre, the implicit equation, singular points");
  formula->add_option("--curves", formula_options.curves_path, "CURVES.json")->required();
  formula->add_option("--curve", formula_options.curve_id, "Only the curve with this id");
  formula->add_option("--base-points", formula_base,
                      "Comma-separated parameters (or inf) of the formula's free base points: a conic's centre "
                      "(default inf: P(infinity)), from degree 4 up to n - 3 of them");
  formula->add_flag("--json", formula_options.json, "One JSON object on stdout");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  try {
    if (stress->parsed()) {
      stress_options.threads = checked_threads(stress_threads);
      const ParallelismLimit parallelism(stress_options.threads);
      stress_options.families = bezinv::cli::parse_families(stress_families);
      stress_options.kinds = bezinv::cli::parse_kinds(stress_kinds);
      stress_options.paths = bezinv::cli::parse_paths(stress_paths);
      std::tie(stress_options.min_degree, stress_options.max_degree) = bezinv::cli::parse_degrees(stress_degrees);
      stress_options.baselines = bezinv::cli::parse_baselines(stress_baselines);
      return bezinv::cli::run_stress(stress_options);
    }
    if (convert->parsed()) {
      if (same_file(convert_out, convert_curves))
        throw bezinv::InputError(convert_out + ": --out is the same file as --curves " + convert_curves +
                                 "; refusing to overwrite an input");
      check_output_directory(convert_out);
      bezinv::remove_temporary_outputs_on_signals();
      return bezinv::cli::run_convert(convert_curves, convert_out);
    }
    if (formula->parsed()) {
      formula_options.base_parameters = bezinv::cli::parse_base_parameters(formula_base);
      return bezinv::cli::run_formula(formula_options);
    }
    if (invert->parsed()) {
      if (!invert_rows.empty()) {
        try {
          std::tie(invert_arguments.selection.begin, invert_arguments.selection.end) =
              bezinv::cli::parse_row_range(invert_rows);
        } catch (const std::invalid_argument& e) {
          throw bezinv::InputError(std::string("--rows ") + e.what());
        }
      }
      invert_arguments.threads = checked_threads(invert_threads);
      check_chunk_points(invert_arguments.chunk_points);
      check_output_is_not_an_input(invert_arguments);
      const ParallelismLimit parallelism(invert_arguments.threads);
      bezinv::remove_temporary_outputs_on_signals();
      return run_invert(invert_arguments);
    }
    if (merge->parsed()) {
      if (merge_points.empty() && merge_rows_option->count() == 0)
        throw bezinv::InputError("bezinv merge: give --points POINTS.npy or --total N (the rows the parts share)");
      std::uint64_t rows = merge_rows;
      if (!merge_points.empty()) rows = bezinv::npy_rows(merge_points);
      std::vector<bezinv::cli::MergePart> parts;
      for (const std::string& text : merge_parts) parts.push_back(bezinv::cli::parse_merge_part(text));
      check_output_directory(merge_out);
      for (const auto& p : parts)
        if (same_file(merge_out, p.path))
          throw bezinv::InputError(merge_out + ": --out is the same file as the part " + p.path);
      bezinv::remove_temporary_outputs_on_signals();
      return bezinv::cli::run_merge(rows, std::move(parts), merge_out);
    }
    if (demo->parsed()) {
      const int threads = checked_threads(demo_threads);
      const ParallelismLimit parallelism(threads);
      return bezinv::cli::run_demo(demo_points, threads);
    }
    if (profile->parsed()) {
      profile_options.threads = checked_threads(profile_threads);
      const ParallelismLimit parallelism(profile_options.threads);
      profile_options.refine = !profile_no_refine;
      profile_options.fast_path = !profile_svd_only;
      bezinv::algebraic_named(profile_algebraic, profile_options.algebraic);  // checked by the parser
      profile_options.off_curve =
          profile_off_curve == "projection" ? bezinv::OffCurve::projection : bezinv::OffCurve::nearest;
      profile_options.kind = profile_kind == "bezier"            ? bezinv::CurveKind::bezier
                             : profile_kind == "rational"        ? bezinv::CurveKind::rational
                                                                 : bezinv::CurveKind::rational_bezier;
      return bezinv::cli::run_profile(profile_options);
    }
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "bezinv: %s\n", e.what());
    return kExitInputError;
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
