// _bezinv: the engine for Python (python/bezinv/__init__.py is the interface users call; this is
// the thin layer under it). Points come in as numpy memory read in place, results go out into a
// numpy array of OUT.npy's records, and the engine runs with the GIL released, through the same
// reader -> invert_stream -> writer path as `bezinv invert`, so the answers are the command's,
// byte for byte.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "bezinv/curve.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/io.hpp"
#include "bezinv/plan.hpp"
#include "stress.hpp"

namespace py = pybind11;

namespace {

// The curves of one file (or dict list), with their plans once plan() has built them: a point's
// curve index refers to this list.
struct Curves {
  std::vector<bezinv::Curve> curves;
  std::vector<bezinv::InversionPlan> plans;  // empty until planned
};

bezinv::InvertOptions options_from(double tol, bool refine, bool fast_path, const std::string& algebraic,
                                   const std::string& off_curve, int threads) {
  bezinv::InvertOptions options;
  options.relative_tolerance = tol;
  options.refine = refine;
  options.fast_path = fast_path;
  bezinv::algebraic_named(algebraic, options.algebraic);  // checked by bezinv.invert
  options.off_curve = off_curve == "projection" ? bezinv::OffCurve::projection : bezinv::OffCurve::nearest;
  options.threads = threads;
  return options;
}

// A curve as pickled: every field, exactly (a composite's parts within it).
py::tuple curve_state(const bezinv::Curve& curve) {
  py::list parts;
  for (const bezinv::Curve& part : curve.curves) parts.append(curve_state(part));
  return py::make_tuple(curve.id, static_cast<int>(curve.kind), curve.x_num, curve.x_den, curve.y_num, curve.y_den,
                        curve.z_num, curve.z_den, curve.spline_degree, curve.knots, parts);
}

bezinv::Curve curve_from_state(const py::tuple& fields) {
  if (fields.size() != 11) throw std::invalid_argument("bezinv.Curves: not a pickled curve");
  bezinv::Curve curve;
  curve.id = fields[0].cast<std::string>();
  curve.kind = static_cast<bezinv::CurveKind>(fields[1].cast<int>());
  curve.x_num = fields[2].cast<std::vector<double>>();
  curve.x_den = fields[3].cast<std::vector<double>>();
  curve.y_num = fields[4].cast<std::vector<double>>();
  curve.y_den = fields[5].cast<std::vector<double>>();
  curve.z_num = fields[6].cast<std::vector<double>>();
  curve.z_den = fields[7].cast<std::vector<double>>();
  curve.spline_degree = fields[8].cast<int>();
  curve.knots = fields[9].cast<std::vector<double>>();
  for (const py::handle part : fields[10].cast<py::list>()) curve.curves.push_back(curve_from_state(part.cast<py::tuple>()));
  return curve;
}

// The index of the curve `selection` names (an id, else a 0-based index, as --curve), or -1.
int curve_named(const std::vector<bezinv::Curve>& curves, const std::string& selection) {
  for (std::size_t i = 0; i < curves.size(); ++i)
    if (curves[i].id == selection) return static_cast<int>(i);
  if (selection.empty() || selection.size() > 9 || selection.find_first_not_of("0123456789") != std::string::npos) return -1;
  const std::size_t index = std::stoul(selection);
  return index < curves.size() ? static_cast<int>(index) : -1;
}

// Rows per task on the in-place path: a task inverts its rows on one thread and packs them while
// their results (56 bytes a row, 0.9 MB) are still in its core's cache. Packing inside the
// parallel tasks, not between engine calls, keeps the Python call at the engine's speed
// (BENCHMARKS.md "Python").
constexpr std::size_t kInPlaceChunkPoints = std::size_t{1} << 14;

// The common case, read in place: planned curves, one plane curve for every row, every coordinate
// finite. No row then needs the reader's checks, and the engine reads the numpy memory as its
// Points a chunk at a time, into a chunk of results packed as the writer packs them. The answers
// are the general path's (the engine's do not depend on how the rows are handed to it, nor on the
// thread count). False when the case is not this one (records partly written then: the caller's
// path writes them all).
bool invert_in_place(const Curves& curves, const bezinv::PointArray& array, std::span<char> records,
                     const bezinv::InvertOptions& options) {
  static_assert(sizeof(bezinv::Point) == 2 * sizeof(double), "a row of (N, 2) float64 is a Point");
  if (curves.plans.empty() || array.width != 2 || array.curve.empty()) return false;
  const int curve = curve_named(curves.curves, array.curve);
  if (curve < 0 || curves.plans[static_cast<std::size_t>(curve)].dimension() != 2) return false;
  const std::size_t rows = array.coordinates.size() / 2;
  const auto* points = reinterpret_cast<const bezinv::Point*>(array.coordinates.data());
  const bezinv::InversionPlan& plan = curves.plans[static_cast<std::size_t>(curve)];
  bezinv::InvertOptions one_thread = options;
  one_thread.threads = 1;
  // Each chunk checks its own coordinates (in its task, not in a pass of its own over them all): a
  // non-finite one anywhere sends the whole call to the reader's path, which answers it
  // invalid_input and rewrites every record.
  std::atomic<bool> all_finite{true};
  auto finite = [](std::span<const double> values) {
    bool ok = true;
    for (const double v : values) ok &= std::isfinite(v);
    return ok;
  };
  tbb::enumerable_thread_specific<std::vector<bezinv::PointResult>> buffers;
  auto invert_chunks = [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<bezinv::PointResult>& results = buffers.local();
    for (std::size_t chunk = range.begin(); chunk != range.end(); ++chunk) {
      const std::size_t begin = chunk * kInPlaceChunkPoints;
      const std::size_t count = std::min(kInPlaceChunkPoints, rows - begin);
      if (!all_finite.load(std::memory_order_relaxed) || !finite(array.coordinates.subspan(2 * begin, 2 * count))) {
        all_finite.store(false, std::memory_order_relaxed);
        return;
      }
      results.resize(count);
      bezinv::invert(plan, std::span(points + begin, count), results, one_thread);
      bezinv::open_results(records.subspan(begin * bezinv::kResultRecordBytes, count * bezinv::kResultRecordBytes))
          ->write(results);
    }
  };
  const std::size_t chunks = (rows + kInPlaceChunkPoints - 1) / kInPlaceChunkPoints;
  if (chunks == 1) {  // too few rows to share out by chunks: the engine shares them out by batches
    if (!finite(array.coordinates)) return false;
    std::vector<bezinv::PointResult> results(rows);
    bezinv::invert(plan, std::span(points, rows), results, options);
    bezinv::open_results(records)->write(results);
  } else if (options.threads == 1) {
    invert_chunks(tbb::blocked_range<std::size_t>(0, chunks));
  } else if (options.threads == 0) {  // every core: TBB's own arena
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), invert_chunks);
  } else {
    tbb::task_arena arena(options.threads);
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), invert_chunks); });
  }
  return all_finite.load();
}

// Inverts `points` (C-contiguous float64, rows x width) into `out` (OUT.npy records, rows of
// them); `reasons` (when asked for) gets each row's reason. The caller checked the shapes.
py::object invert(const Curves& curves, const py::array& points, std::size_t width, const std::string& curve,
                  const py::object& curve_index, py::array& out, double tol, bool refine, bool fast_path,
                  const std::string& algebraic, const std::string& off_curve, int threads, bool want_reasons,
                  bool point_columns) {
  bezinv::PointArray array;
  array.coordinates = std::span(static_cast<const double*>(points.data()), static_cast<std::size_t>(points.size()));
  array.width = width;
  array.curve = curve;
  py::array_t<std::int64_t, py::array::c_style> index;  // held until the engine is done with it
  if (!curve_index.is_none()) {
    index = curve_index.cast<py::array_t<std::int64_t, py::array::c_style>>();
    array.curve_index = std::span(index.data(), static_cast<std::size_t>(index.size()));
  }
  array.name = "points";
  const std::size_t rows = array.coordinates.size() / (width == 0 ? 1 : width);
  bezinv::ResultColumns columns;
  columns.point = point_columns;
  const std::size_t record_bytes = bezinv::result_record_bytes(columns);
  if (static_cast<std::size_t>(out.nbytes()) != rows * record_bytes)
    throw std::invalid_argument("out: " + std::to_string(out.nbytes()) + " bytes for " + std::to_string(rows) + " rows");
  std::vector<const char*> reasons(want_reasons ? rows : 0);
  const bezinv::InvertOptions options = options_from(tol, refine, fast_path, algebraic, off_curve, threads);
  {
    py::gil_scoped_release released;
    const std::span<char> records(static_cast<char*>(out.mutable_data()), static_cast<std::size_t>(out.nbytes()));
    const auto reader = bezinv::open_points(array, curves.curves);  // checks the array as a whole first
    const auto writer = bezinv::open_results(records, std::span(reasons), columns);
    const bool answered_in_place = !want_reasons && !point_columns && invert_in_place(curves, array, records, options);
    if (!answered_in_place && !curves.plans.empty()) {
      bezinv::invert_stream(*reader, *writer, std::span<const bezinv::InversionPlan>(curves.plans), options);
    } else if (!answered_in_place) {
      try {
        bezinv::invert_stream(*reader, *writer, std::span<const bezinv::Curve>(curves.curves), options);
      } catch (const bezinv::PlansError& e) {
        throw bezinv::InputError("curves[" + std::to_string(e.index) + "]: " + e.what());
      }
    }
  }
  if (!want_reasons) return py::none();
  py::list list(rows);
  for (std::size_t i = 0; i < rows; ++i) list[i] = py::str(reasons[i]);
  return list;
}

// The seconds bezinv::invert itself takes on the points of one plane curve (C++ spans, no reader,
// no records), for holding the Python call's time against (bench/python_speed.py).
double engine_seconds(const Curves& curves, const py::array_t<double, py::array::c_style>& points, int curve, int threads) {
  static_assert(sizeof(bezinv::Point) == 2 * sizeof(double));
  if (curves.plans.empty() || curve < 0 || static_cast<std::size_t>(curve) >= curves.plans.size() ||
      points.ndim() != 2 || points.shape(1) != 2 || curves.plans[static_cast<std::size_t>(curve)].dimension() != 2)
    throw std::invalid_argument("engine_seconds: planned curves, a plane curve's index and (N, 2) points");
  const std::size_t rows = static_cast<std::size_t>(points.shape(0));
  const std::span<const bezinv::Point> view(reinterpret_cast<const bezinv::Point*>(points.data()), rows);
  bezinv::InvertOptions options;
  options.threads = threads;
  // Allocated and touched before the clock starts, as a caller who reuses its results does (the
  // Python call is timed with out= reused, bench/python_speed.py).
  std::vector<bezinv::PointResult> results(rows);
  py::gil_scoped_release released;
  const auto start = std::chrono::steady_clock::now();
  bezinv::invert(curves.plans[static_cast<std::size_t>(curve)], view, results, options);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

PYBIND11_MODULE(_bezinv, m) {
  m.doc() = "bezinv's engine (use the bezinv package, which wraps it)";
  py::register_exception<bezinv::InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<bezinv::CurveError>(m, "CurveError", PyExc_ValueError);

  py::class_<bezinv::Curve>(m, "Curve")
      .def_readonly("id", &bezinv::Curve::id)
      .def_property_readonly("kind", [](const bezinv::Curve& c) { return std::string(bezinv::to_string(c.kind)); })
      .def_property_readonly("degree", &bezinv::Curve::degree)
      .def_property_readonly("dimension", &bezinv::Curve::dimension)
      .def_property_readonly("knots", [](const bezinv::Curve& c) { return c.knots; })  // nurbs
      .def_property_readonly("parts", [](const bezinv::Curve& c) { return c.curves; })  // composite
      .def("point", [](const bezinv::Curve& c, double t) -> py::tuple {
        const auto p = c.point3(t);
        if (c.dimension() == 3) return py::make_tuple(p[0], p[1], p[2]);
        return py::make_tuple(p[0], p[1]);
      }, py::arg("t"), "P(t) in the curve's own parameter (nurbs: the knots'; composite: segment + local t)")
      .def("__repr__", [](const bezinv::Curve& c) {
        return "<bezinv.Curve id=" + std::string(py::repr(py::str(c.id))) + " kind=" + bezinv::to_string(c.kind) +
               " degree=" + std::to_string(c.degree()) + " dimension=" + std::to_string(c.dimension()) + ">";
      });

  py::class_<Curves, std::shared_ptr<Curves>>(m, "Curves")
      .def("__len__", [](const Curves& c) { return c.curves.size(); })
      .def("__getitem__", [](const Curves& c, std::ptrdiff_t i) {
        const auto size = static_cast<std::ptrdiff_t>(c.curves.size());
        if (i < 0) i += size;
        if (i < 0 || i >= size) throw py::index_error("curve index out of range");
        return c.curves[static_cast<std::size_t>(i)];
      })
      .def_property_readonly("planned", [](const Curves& c) { return !c.plans.empty(); })
      .def("degrees", [](const Curves& c) {  // effective degrees (plans), as InversionPlan::degree
        std::vector<int> degrees;
        for (const auto& p : c.plans) degrees.push_back(p.degree());
        return degrees;
      })
      .def("diagonals", [](const Curves& c) {
        std::vector<double> diagonals;
        for (const auto& p : c.plans) diagonals.push_back(p.diagonal());
        return diagonals;
      })
      // Pickled (for dask workers, multiprocessing) as the curves' coefficients, exactly; the plans
      // are built again where they are unpickled, as make_plans built them here.
      .def(py::pickle(
          [](const Curves& c) {
            py::list curves;
            for (const bezinv::Curve& curve : c.curves) curves.append(curve_state(curve));
            return py::make_tuple(curves, !c.plans.empty());
          },
          [](const py::tuple& state) {
            auto c = std::make_shared<Curves>();
            for (const py::handle item : state[0].cast<py::list>()) {
              bezinv::Curve curve = curve_from_state(item.cast<py::tuple>());
              bezinv::validate(curve);
              c->curves.push_back(std::move(curve));
            }
            if (state[1].cast<bool>()) c->plans = bezinv::make_plans(std::span<const bezinv::Curve>(c->curves));
            return c;
          }));

  m.def("read_curves", [](const std::string& path) {
    auto curves = std::make_shared<Curves>();
    curves->curves = bezinv::read_curves_json(path);
    return curves;
  });
  m.def("parse_curves", [](const std::string& text, const std::string& name) {
    auto curves = std::make_shared<Curves>();
    curves->curves = bezinv::parse_curves_json(text, name);
    return curves;
  });
  m.def("plan", [](const Curves& curves, int threads) {
    auto planned = std::make_shared<Curves>();
    planned->curves = curves.curves;
    {
      py::gil_scoped_release released;
      try {
        planned->plans = bezinv::make_plans(std::span<const bezinv::Curve>(planned->curves), threads);
      } catch (const bezinv::PlansError& e) {
        throw bezinv::InputError("curves[" + std::to_string(e.index) + "]: " + e.what());
      }
    }
    return planned;
  });
  m.def("invert", &invert);
  m.def("engine_seconds", &engine_seconds);
  // bezinv stress, as its --json prints it (the lists as the command's options spell them; their
  // parsers name a bad item with std::invalid_argument, a ValueError here).
  m.def("stress", [](const std::string& families, const std::string& kinds, const std::string& degrees,
                     std::size_t points, int curves, unsigned long long seed, const std::string& paths, double tol,
                     int threads) {
    bezinv::cli::StressOptions options;
    if (!families.empty()) options.families = bezinv::cli::parse_families(families);
    options.kinds = bezinv::cli::parse_kinds(kinds);
    std::tie(options.min_degree, options.max_degree) = bezinv::cli::parse_degrees(degrees);
    options.points = points;
    options.curves = curves;
    options.seed = seed;
    options.paths = bezinv::cli::parse_paths(paths);
    options.relative_tolerance = tol;
    options.threads = threads;
    py::gil_scoped_release released;
    return bezinv::cli::stress_json(options);
  });
  m.def("result_descr", [](bool point_columns) {
    bezinv::ResultColumns columns;
    columns.point = point_columns;
    return std::string(bezinv::result_descr(columns));
  }, py::arg("point_columns") = false);
  m.def("status_names", [] {
    std::vector<std::string> names;
    for (int s = 0; s <= static_cast<int>(bezinv::Status::failed); ++s)
      names.emplace_back(bezinv::to_string(static_cast<bezinv::Status>(s)));
    return names;
  });
  m.def("path_names", [] {
    std::vector<std::string> names;
    for (int p = 0; p <= static_cast<int>(bezinv::Path::projection); ++p)
      names.emplace_back(bezinv::to_string(static_cast<bezinv::Path>(p)));
    return names;
  });
  m.def("kernel", [] { return std::string(bezinv::active_kernel_name()); });
  m.attr("default_relative_tolerance") = bezinv::kDefaultRelativeTolerance;
}
