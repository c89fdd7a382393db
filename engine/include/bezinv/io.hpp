#pragma once
// The file formats of `bezinv invert` (README "File formats").
//   CURVES.json  {"curves": [CURVE, ...]}, CURVE one of
//                {"id": "a", "kind": "bezier", "points": [[x,y], ...]}
//                {"id": "b", "kind": "rational_bezier", "points": [[x,y], ...], "weights": [w0, ...]}
//                {"id": "c", "kind": "rational", "x_num": [...], "x_den": [...], "y_num": [...], "y_den": [...]}
//                space curves alike: points [x,y,z]; kind rational with "z_num" and "z_den" too
//                {"id": "m", "kind": "matrix_weighted_bezier", "points": [...], then one of "matrices": [M_0, ...];
//                 "normals", "omegas", "mus" (Yang's eq. (2)); "tangents", "omegas", "mus" (eq. (3))}
//   POINTS.csv   header `curve,x,y` or `curve,x,y,z`; curve is an id or a 0-based index into the
//                list; z is given for a space curve's point and empty (or absent) for a plane one's
//   POINTS.npy   float64 '<f8', shape (N, 2) or (N, 3), C order: x, y (, z) per row; the curve comes
//                from a CurveSelection (one curve for all, or an int32/int64 (N,) .npy of curve
//                indices); a row's width must match its curve's dimension
//   OUT.csv      header, then one row per input point, in input order
//   OUT.npy      structured (N,) array: t, residual, t2, sigma_min, sigma_next '<f8', status, path 'u1'
//                (the codes are the enum values of Status and Path in invert.hpp)
// A path ending in ".npy" is a .npy file, anything else CSV. Files of any size stream through in
// chunks (open_points -> invert_stream -> open_results), so memory does not grow with the input.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/matrix_weighted.hpp"

namespace bezinv {

// A whole input cannot be used. what() is one line naming the file and the line or field,
// e.g. "points.csv:1: header must be 'curve,x,y'" or "curves.json: curves[2] (id \"c\"): weights: ...".
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Parses and validates every curve. Throws InputError (malformed JSON, missing field, empty list,
// duplicate id, a curve failing validate()). A plane matrix-weighted curve comes back converted
// (bezinv/matrix_weighted.hpp: kind rational, degree 2n, the same parameter t), a space one too
// (degree 3n, with z).
std::vector<Curve> read_curves_json(const std::string& path);

// The same from CURVES.json text held in memory (a Python dict list, a network message); `name`
// stands for the path in error messages.
std::vector<Curve> parse_curves_json(std::string_view text, const std::string& name = "curves");

// The matrix-weighted curves of CURVES.json as written (plane and space), at their positions in
// the file (nullopt for the other kinds), checked as read_curves_json checks the file.
std::vector<std::optional<MatrixWeightedCurve>> read_matrix_weighted_json(const std::string& path);

// Writes `contents` to `path` all or nothing, as OUT is written (README "Where OUT goes"): a
// failed write leaves an existing file as it was. Throws InputError naming the path.
void write_text_file(const std::string& path, std::string_view contents);

// One data row of POINTS.csv. curve >= 0 indexes the curve list; a row that cannot be used
// (unknown id, index past the end, non-finite or unparsable coordinate) has curve = -1 and a
// static reason; it still gets its output row.
struct PointRow {
  int curve = -1;
  Point point{PointResult::nan, PointResult::nan};
  const char* reason = "";
  double z = PointResult::nan;  // a space curve's point's third coordinate
};

// Where the points of a .npy file find their curve (a CSV names it in its `curve` column, and
// giving either of these with a CSV is an InputError). Exactly one must be set for .npy points.
struct CurveSelection {
  std::string curve;        // `--curve`: an id, or a 0-based index, for every point
  std::string index_path;   // `--curve-index`: int32 or int64 (N,) .npy, 0-based curve index per point
  // `--rows A:B`: only rows [begin, end) of a .npy (end past the last row: to the last), so that
  // machines can share one file; a CSV with a range is an InputError.
  std::uint64_t begin = 0, end = UINT64_MAX;
};

// Points held in memory: `rows` rows of `width` (2 or 3) doubles, x, y (, z), C order, and the
// curve of every row: one curve for all (an id or a 0-based index, as --curve), or a 0-based
// index per row (as --curve-index). The rows are checked as a POINTS.npy's are (a non-finite
// coordinate, an index past the end, a row of the other dimension: invalid_input with its
// reason); `name` stands for the path in errors. The memory is read in place, a chunk at a time,
// and must outlive the reader.
struct PointArray {
  std::span<const double> coordinates;  // rows x width
  std::size_t width = 2;
  std::string curve;                          // one curve for every row, or
  std::span<const std::int64_t> curve_index;  // a curve index per row (rows entries)
  std::string name = "points";
};

// How far a reader has got, for a progress display. Totals are 0 when unknown (a CSV's row count;
// the size of a pipe).
struct ReadProgress {
  std::uint64_t points = 0, points_total = 0;
  std::uint64_t bytes = 0, bytes_total = 0;
};

// Points in input order, a chunk at a time. Whole-file problems throw InputError when they are
// met, which may be after many chunks (a malformed CSV row at line 5,000,000): the caller must
// not have published anything by then (ResultWriter keeps its output temporary until commit).
class PointReader {
 public:
  virtual ~PointReader() = default;
  // Fills rows from the front; returns how many. Fewer than rows.size() only at the end; 0 after it.
  virtual std::size_t read(std::span<PointRow> rows) = 0;
  virtual ReadProgress progress() const = 0;
};

// POINTS.csv or POINTS.npy (by extension). Throws InputError for an unusable header at once, and
// for a row range that starts past the last row.
std::unique_ptr<PointReader> open_points(const std::string& path, const std::vector<Curve>& curves,
                                         const CurveSelection& selection = {});

// Reads a PointArray. Throws InputError at once for a width that is not 2 or 3, coordinates not
// a whole number of rows, a curve that is not there or of the other dimension, or an index array
// of another length.
std::unique_ptr<PointReader> open_points(const PointArray& points, const std::vector<Curve>& curves);

// Results in input order, a chunk at a time. A regular file (or one reached by a symbolic link)
// is written to a temporary file beside it that commit() renames over it (atomic within a
// directory; the old file's mode and, for root, owner carry over) or, when it has other hard
// links, copies into it in place. Destroyed without commit() (an exception on the way), the
// writer removes the temporary and leaves the target as it was. A character device or FIFO is
// written straight through. Failures throw InputError "<path>: cannot write: <reason>".
// Optional columns of OUT after the fixed ones (`bezinv invert --columns point`).
struct ResultColumns {
  // x_t, y_t, z_t: P(t), the curve's point at the row's t (in the curve's own parameter: a NURBS
  // curve's knots, a composite's segment + local t; on the extension where t is outside the
  // segment); z_t is 0 for a plane curve; all three nan where t is nan.
  bool point = false;
};

class ResultWriter {
 public:
  virtual ~ResultWriter() = default;
  // The optional columns it writes; with `point`, give each row's P(t) to write_with_points
  // (write alone then writes them nan).
  virtual ResultColumns columns() const { return {}; }
  virtual void write(std::span<const PointResult> results) = 0;
  // at[i] is P(t) of results[i] (as long as results, or empty: nan); columns it does not write are ignored.
  virtual void write_with_points(std::span<const PointResult> results, std::span<const Point3> at) {
    (void)at;
    write(results);
  }
  virtual void commit() = 0;
};

// OUT.csv or OUT.npy (by extension). CSV columns: t,status,residual,t2,sigma_min,sigma_next,path,
// reason; numbers in the shortest form that reads back to the same double (std::to_chars, so
// round-trip precision), `nan` when absent. `threads` formats CSV rows in parallel (0: all cores).
// The .npy header is written with room for any row count and rewritten with the count at commit.
// With columns.point, CSV gains x_t,y_t,z_t after reason and the .npy record three '<f8' fields
// of those names after path (kResultRecordBytes + kPointColumnsBytes a row).
std::unique_ptr<ResultWriter> open_results(const std::string& path, int threads = 0, ResultColumns columns = {});

// OUT.npy's records in memory: the bytes of its data, row after row (kResultRecordBytes each, the
// fields of kResultDescr), written from the front of `records`, which must hold every row
// written; `reasons` (optional, as long) gets each row's reason. commit() does nothing.
inline constexpr std::size_t kResultRecordBytes = 5 * 8 + 2;
inline constexpr std::size_t kPointColumnsBytes = 3 * 8;
// numpy's descr of the record, as OUT.npy's header writes it (with the point columns: their fields
// after path, kResultRecordBytes + kPointColumnsBytes a record).
std::string_view result_descr(ResultColumns columns = {});
std::size_t result_record_bytes(ResultColumns columns = {});  // kResultRecordBytes (+ kPointColumnsBytes)
std::unique_ptr<ResultWriter> open_results(std::span<char> records, std::span<const char*> reasons = {},
                                           ResultColumns columns = {});

// For commands: SIGINT, SIGTERM and SIGHUP (unless ignored) remove the temporary file of every
// open ResultWriter, then end the process by the same signal. Call once, before open_results.
void remove_temporary_outputs_on_signals();

// The number of rows of a POINTS.npy (its shape's first entry), from its header alone. Throws
// InputError as open_points does for a file that is not one.
std::uint64_t npy_rows(const std::string& path);

// OUT.npy read back a chunk at a time (bezinv merge), the rows as written (reason is not stored in
// a .npy: empty). Throws InputError naming the file for one that is not an OUT.npy (with or
// without the point columns).
class ResultReader {
 public:
  virtual ~ResultReader() = default;
  virtual std::uint64_t rows() const = 0;
  virtual ResultColumns columns() const = 0;
  // Fills results (and, when not empty, `at` with the point columns: nan without them) from the
  // front; returns how many (0 at the end).
  virtual std::size_t read(std::span<PointResult> results, std::span<Point3> at = {}) = 0;
};
std::unique_ptr<ResultReader> open_results_npy(const std::string& path);

// OUT.csv at once (small results, tests): open_results, write, commit.
void write_results_csv(const std::string& path, std::span<const PointResult> results);

// Points per chunk of invert_stream: about 100 MB of rows and results in flight.
constexpr std::size_t kDefaultChunkPoints = std::size_t{1} << 20;

struct StreamSummary {
  std::uint64_t points = 0;
  std::array<std::uint64_t, 6> by_status{};  // indexed by Status
  std::uint64_t plans_built = 0;               // curves whose plan was built (the curves overload)
};

// read a chunk -> invert -> write its results, until the reader is done. Rows the reader rejected
// become invalid_input with its reason. `on_progress` (optional) is called every 65536 points
// inverted and at the end of every chunk, with `points` = points inverted so far (bytes: read so
// far). Does not commit: the caller does when everything succeeded.
StreamSummary invert_stream(PointReader& reader, ResultWriter& writer, std::span<const InversionPlan> plans,
                            const InvertOptions& options, std::size_t chunk_points = kDefaultChunkPoints,
                            const std::function<void(const ReadProgress&)>& on_progress = {});

// The same from the curves (validated): each curve's plan is built when the first chunk with a
// point of it arrives, with the other curves new to that chunk in parallel, so a file of 20,000
// curves inverted for two points builds two plans. Throws PlansError (plan.hpp) for a curve whose
// plan cannot be built.
StreamSummary invert_stream(PointReader& reader, ResultWriter& writer, std::span<const Curve> curves,
                            const InvertOptions& options, std::size_t chunk_points = kDefaultChunkPoints,
                            const std::function<void(const ReadProgress&)>& on_progress = {});

}  // namespace bezinv
