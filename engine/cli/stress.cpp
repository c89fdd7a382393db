#include "stress.hpp"

#include <tbb/parallel_for.h>

#include <unistd.h>  // isatty: the progress line is for a person at a terminal only

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <stdexcept>

#include "bezinv/datasets/curve_sampling.hpp"
#include "bezinv/datasets/high_precision_nearest.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"
#include "baselines.hpp"
#include "stress_report.hpp"

namespace bezinv::cli {
namespace {

using datasets::Family;
using datasets::StressRow;
using datasets::StressTally;

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> items;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) items.push_back(item);
  return items;
}

// The value of `values` whose to_string is `name`, if any.
template <class T>
std::optional<T> named(const std::string& name, std::initializer_list<T> values) {
  for (T value : values)
    if (name == to_string(value)) return value;
  return std::nullopt;
}

// "a,b,c" by `parse` (an optional per item); an unknown item or an empty list throws
// std::invalid_argument naming the option and the item.
template <class T, class Parse>
std::vector<T> parse_list(const std::string& list, const char* option, const char* what, Parse parse) {
  std::vector<T> values;
  for (const std::string& item : split(list)) {
    const std::optional<T> value = parse(item);
    if (!value) throw std::invalid_argument(std::string(option) + ": unknown " + what + " '" + item + "'");
    values.push_back(*value);
  }
  if (values.empty()) throw std::invalid_argument(std::string(option) + ": no " + what + " given");
  return values;
}

// One curve of one cell and its rows.
struct CurveRows {
  Family family;
  CurveKind kind;
  int degree;
  std::optional<InversionPlan> plan;
  std::vector<StressRow> rows;
};

// One line of the report.
struct Cell {
  Family family;
  CurveKind kind;
  int degree;
  std::string path;       // the engine's path, or the baseline library
  bool baseline = false;  // a library's nearest point, not bezinv: no status of its own
  StressTally tally;
  double seconds = 0;
};

// "bezinv stress: making the truths 37% (12 s)" on stderr, rewritten in place, for a person at a
// terminal only (never in a pipe or a file). Called from any thread; one prints per percent.
class Progress {
 public:
  Progress(const char* stage, std::size_t total)
      : stage_(stage), total_(total), enabled_(::isatty(STDERR_FILENO) == 1 && total > 0),
        start_(std::chrono::steady_clock::now()) {}
  ~Progress() {
    if (enabled_) std::fprintf(stderr, "\r\033[K");
  }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  void step() {
    if (!enabled_) return;
    const std::size_t done = ++done_;
    const std::size_t percent = 100 * done / total_;
    std::size_t shown = shown_.load();
    if (percent <= shown || !shown_.compare_exchange_strong(shown, percent)) return;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::fprintf(stderr, "\rbezinv stress: %s %zu%% (%.0f s)", stage_, percent, seconds);
  }

 private:
  const char* stage_;
  std::size_t total_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
  std::atomic<std::size_t> done_{0}, shown_{0};
};

InvertOptions options_for(StressPath path, const StressOptions& options) {
  InvertOptions o;
  o.relative_tolerance = options.relative_tolerance;
  o.threads = options.threads;
  o.fast_path = path != StressPath::svd_only;
  o.refine = path != StressPath::no_refine;
  if (path == StressPath::formula) o.algebraic = Algebraic::formula;
  if (path == StressPath::projection) o.off_curve = OffCurve::projection;
  return o;
}

nlohmann::json quantiles_json(const std::vector<double>& values) {
  const datasets::Quantiles q = datasets::quantiles(values);
  auto number = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
  return {{"p50", number(q.p50)}, {"p99", number(q.p99)}, {"p999", number(q.p999)}, {"max", number(q.max)}};
}

}  // namespace

const char* to_string(StressPath path) {
  switch (path) {
    case StressPath::default_path: return "default";
    case StressPath::svd_only: return "svd-only";
    case StressPath::formula: return "formula";
    case StressPath::projection: return "projection";
    case StressPath::no_refine: return "no-refine";
  }
  return "?";
}

std::vector<Family> parse_families(const std::string& list) {
  return parse_list<Family>(list, "--families", "family", datasets::family_from_string);
}

std::string all_families() {
  std::string list;
  for (Family family : datasets::kFamilies) {
    if (!list.empty()) list += ',';
    list += datasets::to_string(family);
  }
  return list;
}

std::vector<CurveKind> parse_kinds(const std::string& list) {
  return parse_list<CurveKind>(list, "--kinds", "kind", [](const std::string& item) {
    return named(item, {CurveKind::bezier, CurveKind::rational_bezier, CurveKind::rational});
  });
}

std::vector<StressPath> parse_paths(const std::string& list) {
  return parse_list<StressPath>(list, "--paths", "path", [](const std::string& item) {
    return named(item, {StressPath::default_path, StressPath::svd_only, StressPath::no_refine, StressPath::formula,
                        StressPath::projection});
  });
}

std::pair<int, int> parse_degrees(const std::string& range) {
  int lo = 0, hi = 0;
  char extra = 0;
  const int read = std::sscanf(range.c_str(), "%d-%d%c", &lo, &hi, &extra);
  if (read == 1) hi = lo;
  if ((read != 1 && read != 2) || lo < 1 || hi < lo || hi > kMaxDegree)
    throw std::invalid_argument("--degrees: expected N or LO-HI within 1-" + std::to_string(kMaxDegree) + ", got '" +
                                range + "'");
  return {lo, hi};
}

std::vector<baselines::Library> parse_baselines(const std::string& list) {
  std::vector<baselines::Library> libraries;
  for (const std::string& item : split(list)) {
    baselines::Library library;
    if (item == "occt") library = baselines::Library::occt;
    else if (item == "sisl") library = baselines::Library::sisl;
    else throw std::invalid_argument("--baseline: unknown library '" + item + "' (occt, sisl)");
    if (!baselines::available(library))
      throw std::invalid_argument("--baseline " + item + ": this bezinv was built without it (scripts/bench.sh "
                                  "installs OpenCASCADE and SISL and builds bezinv with them)");
    if (library == baselines::Library::sisl && !baselines::stack_is_large())
      throw std::invalid_argument("--baseline sisl: SISL's s1953 can overflow an 8 MiB stack; run under "
                                  "`ulimit -s unlimited`");
    libraries.push_back(library);
  }
  return libraries;
}

namespace {

// What a run found: its cells and the JSON object --json prints, with the totals.
struct StressRun {
  std::vector<Cell> cells;
  nlohmann::json out;
  double generation_seconds = 0;
  std::size_t rows = 0, wrong = 0, nan_t = 0, missing_t2 = 0;
};

// The whole run; `report` (--report), when given, collects every row for the page.
StressRun run(const StressOptions& options, StressReport* report) {
  // 1. The curves and their rows, truths included, in parallel (the high-precision truth is the
  //    expensive part).
  std::vector<CurveRows> curves;
  for (Family family : options.families)
    for (CurveKind kind : options.kinds)
      for (int degree = options.min_degree; degree <= options.max_degree; ++degree)
        for (int c = 0; c < options.curves; ++c) curves.push_back({family, kind, degree, std::nullopt, {}});
  const std::size_t per_curve = std::max<std::size_t>(1, options.points / curves.size());
  const auto generation_start = std::chrono::steady_clock::now();
  Progress making("making the points and their truths", curves.size());
  tbb::parallel_for(std::size_t{0}, curves.size(), [&](std::size_t i) {
    CurveRows& c = curves[i];
    struct Step {
      Progress& progress;
      ~Step() { progress.step(); }
    } step{making};
    std::mt19937_64 rng(options.seed + 1000003ULL * i);
    // Half the curves "reasonable" (a perturbed arc), half wild (loops, close approaches).
    const int index = static_cast<int>(i % static_cast<std::size_t>(options.curves));
    const std::optional<datasets::StressCurve> curve = datasets::stress_curve(c.family, c.kind, c.degree, index, rng);
    if (!curve) return;  // the family does not apply here
    InversionPlan plan = make_plan(curve->space ? *curve->space : curve->curve);  // the engine's curve
    if (!plan.usable()) return;
    const datasets::CurveSampling sampling(curve->curve);
    c.rows = datasets::stress_rows(c.family, *curve, sampling, static_cast<int>(per_curve), options.relative_tolerance,
                                   rng);
    c.plan.emplace(std::move(plan));
  });
  const double generation_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - generation_start).count();

  // 2. Every path over every cell's curves.
  StressRun result;
  result.generation_seconds = generation_seconds;
  std::vector<Cell>& cells = result.cells;
  const bool reporting = report != nullptr;
  for (StressPath path : options.paths) {
    const InvertOptions invert_options = options_for(path, options);
    for (std::size_t first = 0; first < curves.size(); first += static_cast<std::size_t>(options.curves)) {
      Cell cell{curves[first].family, curves[first].kind, curves[first].degree, to_string(path), false, {}, 0.0};
      for (std::size_t i = first; i < first + static_cast<std::size_t>(options.curves); ++i) {
        const CurveRows& c = curves[i];
        if (!c.plan || c.rows.empty()) continue;
        const bool space = c.plan->dimension() == 3;
        std::vector<Point> points;
        std::vector<Point3> space_points;
        for (const StressRow& row : c.rows) {
          if (space) space_points.emplace_back(row.point.x, row.point.y, row.z);
          else points.push_back(row.point);
        }
        std::vector<PointResult> results(c.rows.size());
        const auto start = std::chrono::steady_clock::now();
        if (space) invert(*c.plan, space_points, results, invert_options);
        else invert(*c.plan, points, results, invert_options);
        cell.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        for (std::size_t k = 0; k < c.rows.size(); ++k) cell.tally.add(c.rows[k], results[k], c.plan->diagonal());
        if (reporting)
          for (std::size_t k = 0; k < c.rows.size(); ++k)
            report->add({c.family, c.kind, c.degree, to_string(path), &c.plan->curve()}, c.rows[k], results[k]);
      }
      if (cell.tally.rows > 0) cells.push_back(std::move(cell));  // a family that does not apply here
    }
  }
  // The baselines: each library's nearest point of the segment for the rows whose truth is one
  // (not the extension's, which they do not look for), one point at a time as their users call
  // them. They give no status: a row counts as answered with its expected one, and its t is
  // compared (for a double point, with the nearer of the two parameters).
  for (baselines::Library library : options.baselines) {
    for (std::size_t first = 0; first < curves.size(); first += static_cast<std::size_t>(options.curves)) {
      Cell cell{curves[first].family, curves[first].kind, curves[first].degree, baselines::to_string(library), true, {},
                0.0};
      for (std::size_t i = first; i < first + static_cast<std::size_t>(options.curves); ++i) {
        const CurveRows& c = curves[i];
        if (!c.plan || c.rows.empty() || c.plan->dimension() == 3) continue;  // plane curves only
        const auto projector = baselines::projector(library, c.plan->curve());
        if (!projector) continue;  // separate denominators: not a curve the library takes
        for (const StressRow& row : c.rows) {
          if (row.expected == Status::outside_segment) continue;
          const auto start = std::chrono::steady_clock::now();
          PointResult got;
          got.status = row.expected;
          got.t = projector->parameter(row.point);
          if (reporting) report->add_baseline(c.family, baselines::to_string(library), row, got.t);
          cell.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          got.residual = PointResult::nan;  // the library's distance is not asked for
          StressRow compared = row;
          compared.acceptable = 1u << static_cast<unsigned>(row.expected);
          if (row.expected == Status::double_point) {  // either branch's parameter is right
            compared.expected = Status::ok;
            got.status = Status::ok;
            if (std::abs(got.t - row.t2_true) < std::abs(got.t - row.t_true)) compared.t_true = row.t2_true;
            compared.acceptable = 1u << static_cast<unsigned>(Status::ok);
          }
          cell.tally.add(compared, got, c.plan->diagonal());
        }
      }
      if (cell.tally.rows > 0) cells.push_back(std::move(cell));
    }
  }

  // 3. The totals and the JSON object.
  std::size_t& rows = result.rows;
  std::size_t& wrong = result.wrong;
  std::size_t& nan_t = result.nan_t;
  std::size_t& missing_t2 = result.missing_t2;
  for (const Cell& cell : cells) {
    if (cell.baseline) continue;
    rows += cell.tally.rows;
    wrong += cell.tally.wrong_status;
    nan_t += cell.tally.nan_t;
    missing_t2 += cell.tally.missing_t2;
  }
  {
    nlohmann::json& out = result.out;
    out["command"] = "stress";
    out["seed"] = options.seed;
    out["relative_tolerance"] = options.relative_tolerance;
    out["rows"] = rows;
    out["wrong_status"] = wrong;
    out["nan_t"] = nan_t;
    out["missing_t2"] = missing_t2;
    out["generation_seconds"] = generation_seconds;
    out["cells"] = nlohmann::json::array();
    for (const Cell& cell : cells) {
      const StressTally& t = cell.tally;
      nlohmann::json confusion = nlohmann::json::object();
      for (std::size_t e = 0; e < datasets::kStatusCount; ++e)
        for (std::size_t g = 0; g < datasets::kStatusCount; ++g)
          if (t.confusion[e][g])
            confusion[bezinv::to_string(static_cast<Status>(e))][bezinv::to_string(static_cast<Status>(g))] =
                t.confusion[e][g];
      out["cells"].push_back({{"family", to_string(cell.family)},
                              {"kind", bezinv::to_string(cell.kind)},
                              {"degree", cell.degree},
                              {"path", cell.path},
                              {"baseline", cell.baseline},
                              {"rows", t.rows},
                              {"wrong_status", t.wrong_status},
                              {"ambiguous", t.ambiguous},
                              {"nan_t", t.nan_t},
                              {"missing_t2", t.missing_t2},
                              {"no_truth", t.no_truth},
                              {"confusion", confusion},
                              {"abs_dt", quantiles_json(t.dt)},
                              {"abs_dt_over_bound", quantiles_json(t.dt_over_bound)},
                              {"residual_error_over_diagonal", quantiles_json(t.residual_error)},
                              {"points_per_second", cell.seconds > 0 ? t.rows / cell.seconds : 0.0}});
    }
  }
  return result;
}

}  // namespace

std::string stress_json(const StressOptions& options) { return run(options, nullptr).out.dump(2); }

int run_stress(const StressOptions& options) {
  StressReport report;
  const bool reporting = !options.report_directory.empty();
  const StressRun result = run(options, reporting ? &report : nullptr);
  const std::vector<Cell>& cells = result.cells;
  const std::size_t rows = result.rows, wrong = result.wrong, nan_t = result.nan_t, missing_t2 = result.missing_t2;
  const double generation_seconds = result.generation_seconds;
  if (options.json) std::printf("%s\n", result.out.dump(2).c_str());
  if (reporting) {
    try {
      report.write(options.report_directory, result.out);
    } catch (const std::exception& e) {  // a directory or file that cannot be written: named
      std::fprintf(stderr, "bezinv: stress --report: %s\n", e.what());
      return 2;
    }
  }
  if (!options.json) {
    std::printf("bezinv stress: %zu rows, seed %llu, tolerance %.3g x diagonal (truths at %d bits, made in %.1f s)\n\n",
                rows, options.seed, options.relative_tolerance, datasets::kReferenceBits, generation_seconds);
    std::printf("%-10s %-15s %3s %-9s %7s %5s %5s | %-31s | %-19s | %9s %9s\n", "family", "kind", "deg", "path", "rows",
                "wrong", "ambig", "|t - t_true| p50 p99 p99.9 max", "/ bound p99.9 max", "resid", "points/s");
    for (const Cell& cell : cells) {
      const StressTally& t = cell.tally;
      const datasets::Quantiles dt = datasets::quantiles(t.dt), ratio = datasets::quantiles(t.dt_over_bound),
                                residual = datasets::quantiles(t.residual_error);
      std::printf("%-10s %-15s %3d %-9s %7zu %5zu %5zu | %7.1e %7.1e %7.1e %7.1e | %9.2g %9.2g | %9.1e %9.3g\n",
                  to_string(cell.family), bezinv::to_string(cell.kind), cell.degree, cell.path.c_str(), t.rows,
                  t.wrong_status, t.ambiguous, dt.p50, dt.p99, dt.p999, dt.max, ratio.p999, ratio.max, residual.p999,
                  cell.seconds > 0 ? t.rows / cell.seconds : 0.0);
    }
    std::printf("\nresid: p99.9 of |residual - true distance| / diagonal. / bound: |t - t_true| over the accuracy\n"
                "model's bound (docs/accuracy-model.md). wrong: a status the contract does not allow; ambig: rows\n"
                "within a margin of the tolerance, where more than one status is right.\n");
    for (const Cell& cell : cells)
      for (std::size_t e = 0; e < datasets::kStatusCount; ++e)
        for (std::size_t g = 0; g < datasets::kStatusCount; ++g)
          if (cell.tally.wrong[e][g])
            std::printf("  %s %s degree %d %s: expected %s, got %s: %zu\n", to_string(cell.family),
                        bezinv::to_string(cell.kind), cell.degree, cell.path.c_str(),
                        bezinv::to_string(static_cast<Status>(e)), bezinv::to_string(static_cast<Status>(g)),
                        cell.tally.wrong[e][g]);
    std::printf("%zu of %zu rows with a wrong status, %zu without t, %zu double points without t2\n", wrong, rows,
                nan_t, missing_t2);
  }
  return wrong == 0 && nan_t == 0 && missing_t2 == 0 ? 0 : 1;
}

}  // namespace bezinv::cli
