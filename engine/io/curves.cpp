// CURVES.json -> std::vector<Curve> (format in bezinv/io.hpp).
//
// The file is parsed through nlohmann's SAX interface rather than json::parse so that every error
// can say where it is: json::parse reports a number that overflows a double ("1e999") as an
// out_of_range exception with no position at all, and silently keeps the last of two equal keys.
// The SAX builder below knows the path it is inside (curves[2].points[1][0]) when either happens.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <iterator>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "bezinv/io.hpp"
#include "bezinv/tolerances.hpp"
#include "quote.hpp"
#include "io/curves_text.hpp"
#include "io/whole_file.hpp"

namespace bezinv {
namespace {

using json = nlohmann::json;
using detail::escaped_excerpt;
using detail::quoted_excerpt;

// The largest CURVES.json read, checked from the file size before reading (and counted while
// reading a pipe or a device). The text, its parse tree and then the plans take about 25 times
// the text (22 MB of 100,000 cubics: 0.54 GB peak), so this admits some 1.2 million cubics in
// about 6.5 GB, and no more, rather than ending in an allocation failure.
constexpr std::uint64_t kMaxCurvesBytes = std::uint64_t{256} << 20;
// The deepest nesting of arrays and objects read: a curve list needs 5 ({"curves": [{"points":
// [[x, y]]}]}), and every level costs a frame, so a file of '[' must not get one per byte.
constexpr std::size_t kMaxJsonDepth = 16;

[[noreturn]] void fail(const std::string& where, const std::string& problem) {
  throw InputError(where + ": " + problem);
}

// 1-based line of a byte offset, for errors nlohmann reports by byte only.
std::size_t line_of(std::string_view text, std::size_t byte) {
  byte = std::min(byte, text.size());
  std::size_t line = 1;
  for (std::size_t i = 0; i < byte; ++i) line += text[i] == '\n';
  return line;
}

// Drops nlohmann's "[json.exception.parse_error.101] " tag: the reader wants the sentence. The
// sentence quotes the file's text between single quotes ("last read: '...'", "number overflow
// parsing '...'"), a whole unterminated string if need be: that part is escaped and cut short.
std::string without_exception_tag(const char* what) {
  std::string_view message(what);
  if (message.starts_with("[json.exception.")) {
    const auto end = message.find("] ");
    if (end != std::string_view::npos) message.remove_prefix(end + 2);
  }
  const std::size_t open = message.find('\'');
  const std::size_t close = message.rfind('\'');
  if (open == std::string_view::npos || close == open) return std::string(message);
  return std::string(message.substr(0, open + 1)) + escaped_excerpt(message.substr(open + 1, close - open - 1)) +
         std::string(message.substr(close));
}

// A key in a path or message: as it is when it is a plain name (all the format's are), else quoted.
std::string key_text(std::string_view key) {
  const bool plain = !key.empty() && key.size() <= 40 && std::all_of(key.begin(), key.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
  return plain ? std::string(key) : quoted_excerpt(key);
}

// Builds the DOM like json::parse, but remembers the path from the root to the value being read,
// rejects duplicate keys, and turns parse errors into one-line InputError text.
class LocatingBuilder : public nlohmann::json_sax<json> {
 public:
  explicit LocatingBuilder(std::string_view text) : text_(text) {}

  json root;
  std::string error;  // set when parsing stopped

  bool null() override { return add(json(nullptr)); }
  bool boolean(bool value) override { return add(json(value)); }
  bool number_integer(number_integer_t value) override { return add(json(value)); }
  bool number_unsigned(number_unsigned_t value) override { return add(json(value)); }
  bool number_float(number_float_t value, const string_t&) override { return add(json(value)); }
  bool string(string_t& value) override { return add(json(std::move(value))); }
  bool binary(binary_t& value) override { return add(json::binary(std::move(value))); }

  bool start_object(std::size_t) override { return open(json::object()); }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(json::array()); }
  bool end_array() override { return close(); }

  bool key(string_t& key) override {
    Frame& top = stack_.back();
    if (top.node->contains(key)) {
      error = path(/*pending_in_array=*/false, /*innermost_key=*/false) + ": duplicate key " + quoted_excerpt(key);
      return false;
    }
    top.key = std::move(key);
    return true;
  }

  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& ex) override {
    // 406 is nlohmann's "number overflow": a literal beyond the double range. Only here is the
    // path exact (the offending value is the one about to be added); for syntax errors it is
    // where the parser was, which is still the best hint.
    if (ex.id == 406) {
      error = "line " + std::to_string(line_of(text_, position)) + ", byte " + std::to_string(position) +
              ": " + path(true, true) + ": " + without_exception_tag(ex.what()) + " (not a finite double)";
    } else {
      error = "malformed JSON at byte " + std::to_string(position) + " (near " + path(true, true) +
              "): " + without_exception_tag(ex.what());
    }
    return false;
  }

 private:
  struct Frame {
    json* node;
    std::string key;  // objects: the key whose value is being read
  };

  // A value goes into the innermost open container (or becomes the root).
  json* insert(json&& value) {
    if (stack_.empty()) {
      root = std::move(value);
      return &root;
    }
    Frame& top = stack_.back();
    if (top.node->is_array()) {
      top.node->push_back(std::move(value));
      return &top.node->back();
    }
    json& slot = (*top.node)[top.key];
    slot = std::move(value);
    return &slot;
  }
  bool add(json&& value) {
    insert(std::move(value));
    return true;
  }
  bool open(json&& container) {
    if (stack_.size() >= kMaxJsonDepth) {
      error = path(true, true) + ": nested deeper than " + std::to_string(kMaxJsonDepth) +
              " arrays and objects (a curve list needs 5)";
      return false;
    }
    json* node = insert(std::move(container));
    stack_.push_back({node, {}});
    return true;
  }
  bool close() {
    stack_.pop_back();
    return true;
  }

  // "curves[2].points[1][0]". pending_in_array: the innermost array's current element has not
  // been inserted yet (so its index is size(), not size() - 1). innermost_key: the innermost
  // object's current key belongs to the path (false while a new key is being read).
  std::string path(bool pending_in_array, bool innermost_key) const {
    std::string out;
    for (std::size_t i = 0; i < stack_.size(); ++i) {
      const json& node = *stack_[i].node;
      const bool innermost = i + 1 == stack_.size();
      if (node.is_array()) {
        std::size_t index = node.size();
        if (!(innermost && pending_in_array) && index > 0) --index;
        // Appended piecewise: "[" + to_string(...) trips a GCC 12 -Wrestrict false positive.
        out += '[';
        out += std::to_string(index);
        out += ']';
      } else if (!stack_[i].key.empty() && (innermost_key || !innermost)) {
        if (!out.empty()) out += '.';
        out += key_text(stack_[i].key);
      }
    }
    return out.empty() ? std::string("top level") : out;
  }

  std::string_view text_;
  std::vector<Frame> stack_;
};

// "a number", "a string", ...: for "expected X, found Y" messages.
std::string a_type_name(const json& value) {
  const std::string name = value.type_name();
  const bool vowel = name.find_first_of("aeiou") == 0;
  return (vowel ? "an " : "a ") + name;
}

double number(const json& value, const std::string& where, const std::string& field) {
  if (!value.is_number()) fail(where, field + ": expected a number, found " + a_type_name(value));
  const double result = value.get<double>();
  // The parser already refuses literals beyond the double range; this guards integers that
  // nlohmann stores exactly but that could not come back as finite doubles (none does).
  if (!std::isfinite(result)) fail(where, field + ": not a finite number");
  return result;
}

const json& required_field(const json& curve, const char* field, const std::string& where) {
  const auto it = curve.find(field);
  if (it == curve.end()) fail(where, std::string(field) + ": missing");
  return *it;
}

std::vector<double> number_list(const json& curve, const char* field, const std::string& where) {
  const json& list = required_field(curve, field, where);
  if (!list.is_array()) fail(where, std::string(field) + ": expected an array of numbers, found " + a_type_name(list));
  if (list.empty()) fail(where, std::string(field) + ": empty list");
  std::vector<double> out;
  out.reserve(list.size());
  for (std::size_t i = 0; i < list.size(); ++i)
    out.push_back(number(list[i], where, std::string(field) + "[" + std::to_string(i) + "]"));
  return out;
}

// Control points [x, y] or [x, y, z], all of one dimension (returned in `dimension`).
std::vector<std::array<double, 3>> point_list(const json& curve, const std::string& where, int& dimension) {
  const json& list = required_field(curve, "points", where);
  if (!list.is_array()) fail(where, "points: expected an array of [x, y] or [x, y, z], found " + a_type_name(list));
  if (list.empty()) fail(where, "points: empty list");
  std::vector<std::array<double, 3>> out;
  out.reserve(list.size());
  dimension = 0;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string field = "points[" + std::to_string(i) + "]";
    const json& point = list[i];
    if (!point.is_array()) fail(where, field + ": expected [x, y] or [x, y, z], found " + a_type_name(point));
    if (point.size() != 2 && point.size() != 3)
      fail(where, field + ": expected [x, y] or [x, y, z], found an array of " + std::to_string(point.size()));
    if (dimension == 0) dimension = static_cast<int>(point.size());
    if (static_cast<int>(point.size()) != dimension)
      fail(where, field + ": " + std::to_string(point.size()) + " coordinates, but points[0] has " +
                      std::to_string(dimension) + " (a curve is plane or space throughout)");
    out.push_back({number(point[0], where, field + "[0]"), number(point[1], where, field + "[1]"),
                   dimension == 3 ? number(point[2], where, field + "[2]") : 0.0});
  }
  return out;
}

// One weight per point, each product w_i P_i within the double range: the curve is stored
// homogeneously (w_i x_i, w_i y_i), and a product beyond the range would reach validate() as a
// non-finite x_num, a field the file does not have.
void check_weights(const std::vector<double>& weights, const std::vector<std::array<double, 3>>& points, int dimension,
                   const std::string& where) {
  if (weights.size() != points.size())
    fail(where, "weights: " + std::to_string(weights.size()) + " weights for " + std::to_string(points.size()) +
                    " points (need one per point)");
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < dimension; ++k)
      if (!std::isfinite(weights[i] * points[i][k]))
        fail(where, "points[" + std::to_string(i) + "]: times weights[" + std::to_string(i) + "] overflows the double range");
}

std::vector<std::array<double, 2>> plane_points(const std::vector<std::array<double, 3>>& points) {
  std::vector<std::array<double, 2>> out;
  for (const auto& p : points) out.push_back({p[0], p[1]});
  return out;
}

// Every field a curve may have, by kind. Any other field is refused rather than ignored: a typo
// ("weight") or a field of another kind (weights on a polynomial "bezier") would otherwise change
// nothing and go unnoticed.
constexpr const char* kAllCurveFields[] = {"id",     "kind",    "points",   "weights", "x_num", "x_den",
                                           "y_num",  "y_den",   "z_num",    "z_den",   "matrices", "normals",
                                           "tangents", "omegas", "mus",     "degree",  "knots", "curves"};

void refuse_other_fields(const json& curve, std::initializer_list<const char*> fields, const char* kind,
                         const std::string& where) {
  const auto among = [](std::string_view key, const auto& names) {
    return std::any_of(std::begin(names), std::end(names), [&](const char* name) { return key == name; });
  };
  for (const auto& [key, value] : curve.items()) {
    if (among(key, fields)) continue;
    if (among(key, kAllCurveFields)) fail(where, key + ": not a field of kind \"" + kind + "\"");
    std::string known;
    for (const char* field : fields) known += (known.empty() ? "" : ", ") + std::string(field);
    fail(where, quoted_excerpt(key) + ": unknown field (kind \"" + kind + "\" has " + known + ")");
  }
}

// POINTS.csv names curves by id in a comma-separated, space-trimmed field, so such an id could
// never be referred to by name; a control character could not be typed there, nor shown.
bool id_fits_points_csv(const std::string& id) {
  if (id.find_first_of(",\"") != std::string::npos) return false;
  if (std::any_of(id.begin(), id.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7F; }))
    return false;
  const auto is_space = [](char c) { return c == ' ' || c == '\t'; };
  return !is_space(id.front()) && !is_space(id.back());
}

// A list of d-vectors (points, normals, tangents): `dimension` 0 takes it from the first entry
// (2 or 3), else each must have that many coordinates.
std::vector<Vector3> vector_list(const json& curve, const char* field, int& dimension, const std::string& where) {
  const json& list = required_field(curve, field, where);
  if (!list.is_array()) fail(where, std::string(field) + ": expected an array of [x, y] or [x, y, z], found " + a_type_name(list));
  if (list.empty()) fail(where, std::string(field) + ": empty list");
  std::vector<Vector3> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string name = std::string(field) + "[" + std::to_string(i) + "]";
    const json& v = list[i];
    if (!v.is_array() || (v.size() != 2 && v.size() != 3))
      fail(where, name + ": expected [x, y] or [x, y, z], found " + (v.is_array() ? "an array of " + std::to_string(v.size()) : a_type_name(v)));
    if (dimension == 0) dimension = static_cast<int>(v.size());
    if (static_cast<int>(v.size()) != dimension)
      fail(where, name + ": " + std::to_string(v.size()) + " coordinates, but the curve is " + std::to_string(dimension) + "D");
    Vector3 e{};
    for (std::size_t c = 0; c < v.size(); ++c) e[c] = number(v[c], where, name + "[" + std::to_string(c) + "]");
    out.push_back(e);
  }
  return out;
}

// {"kind": "matrix_weighted_bezier", "points": [...], and one of "matrices"; "normals", "omegas",
// "mus"; "tangents", "omegas", "mus"}: the curve as written (bezinv/matrix_weighted.hpp).
MatrixWeightedCurve parse_matrix_weighted(const json& entry, std::string id, const std::string& where) {
  MatrixWeightedCurve c;
  c.id = std::move(id);
  c.dimension = 0;  // from the points
  c.points = vector_list(entry, "points", c.dimension, where);
  const std::size_t count = c.points.size();
  const int d = c.dimension;
  auto same_count = [&](const char* field, std::size_t size) {
    if (size != count)
      fail(where, std::string(field) + ": " + std::to_string(size) + " for " + std::to_string(count) +
                      " points (need one per point)");
  };
  const bool has_matrices = entry.contains("matrices"), has_normals = entry.contains("normals"),
             has_tangents = entry.contains("tangents");
  if (has_matrices + has_normals + has_tangents != 1)
    fail(where, "exactly one of matrices, normals (with omegas and mus) or tangents (with omegas and mus) is needed");
  if (has_matrices) {
    refuse_other_fields(entry, {"id", "kind", "points", "matrices"}, "matrix_weighted_bezier", where);
    const json& list = entry["matrices"];
    if (!list.is_array()) fail(where, "matrices: expected an array of matrices, found " + a_type_name(list));
    same_count("matrices", list.size());
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string name = "matrices[" + std::to_string(i) + "]";
      const json& m = list[i];
      if (!m.is_array() || static_cast<int>(m.size()) != d)
        fail(where, name + ": expected a " + std::to_string(d) + " x " + std::to_string(d) + " matrix (the points are " +
                        std::to_string(d) + "D)");
      Matrix3 out{};
      for (int r = 0; r < d; ++r) {
        const json& row = m[static_cast<std::size_t>(r)];
        if (!row.is_array() || static_cast<int>(row.size()) != d)
          fail(where, name + "[" + std::to_string(r) + "]: expected a row of " + std::to_string(d) + " numbers");
        for (int col = 0; col < d; ++col)
          out[static_cast<std::size_t>(3 * r + col)] =
              number(row[static_cast<std::size_t>(col)], where, name + "[" + std::to_string(r) + "][" + std::to_string(col) + "]");
      }
      c.matrices.push_back(out);
    }
    return c;
  }
  const char* vectors = has_normals ? "normals" : "tangents";
  refuse_other_fields(entry, {"id", "kind", "points", vectors, "omegas", "mus"}, "matrix_weighted_bezier", where);
  int vector_dimension = d;
  const std::vector<Vector3> v = vector_list(entry, vectors, vector_dimension, where);
  const std::vector<double> omegas = number_list(entry, "omegas", where), mus = number_list(entry, "mus", where);
  same_count(vectors, v.size());
  same_count("omegas", omegas.size());
  same_count("mus", mus.size());
  for (std::size_t i = 0; i < count; ++i) {
    try {
      c.matrices.push_back(has_normals ? normal_weight(d, v[i], omegas[i], mus[i], "")
                                       : tangent_weight(d, v[i], omegas[i], mus[i], ""));
    } catch (const CurveError& e) {
      fail(where, std::string(vectors) + "[" + std::to_string(i) + "], omegas[" + std::to_string(i) + "], mus[" +
                      std::to_string(i) + "]" + e.what());
    }
  }
  return c;
}

Curve parse_curve(const json& entry, std::string& where, bool part = false);

// {"kind": "nurbs", "degree": p, "knots": [...], "points": [...], optional "weights": [...]}; the
// knot vector and the weights are checked by validate().
Curve parse_nurbs(const json& entry, std::string id, const std::string& where) {
  refuse_other_fields(entry, {"id", "kind", "degree", "knots", "points", "weights"}, "nurbs", where);
  const json& degree_value = required_field(entry, "degree", where);
  if (!degree_value.is_number_integer())
    fail(where, "degree: expected an integer, found " +
                    (degree_value.is_number() ? "the number " + degree_value.dump() : a_type_name(degree_value)));
  const long long degree = degree_value.get<long long>();
  if (degree < 1 || degree > kMaxDegree)
    fail(where, "degree: " + std::to_string(degree) + " is not in 1.." + std::to_string(kMaxDegree));
  int dimension = 0;
  const auto points = point_list(entry, where, dimension);
  const auto knots = number_list(entry, "knots", where);
  std::vector<double> weights;
  if (entry.contains("weights")) {
    weights = number_list(entry, "weights", where);
    check_weights(weights, points, dimension, where);
  }
  return dimension == 3 ? Curve::space_nurbs(std::move(id), static_cast<int>(degree), knots, points, weights)
                        : Curve::nurbs(std::move(id), static_cast<int>(degree), knots, plane_points(points), weights);
}

// {"kind": "composite", "curves": [CURVE, ...]}: each CURVE as at the top level, its id optional;
// the joints are checked by validate().
Curve parse_composite(const json& entry, std::string id, const std::string& where) {
  refuse_other_fields(entry, {"id", "kind", "curves"}, "composite", where);
  const json& list = required_field(entry, "curves", where);
  if (!list.is_array()) fail(where, "curves: expected an array of curves, found " + a_type_name(list));
  if (list.empty()) fail(where, "curves: empty list (need at least one curve)");
  std::vector<Curve> parts;
  for (std::size_t i = 0; i < list.size(); ++i) {
    std::string part_where = where + ": curves[" + std::to_string(i) + "]";
    const json& kind = list[i].is_object() ? list[i].value("kind", json()) : json();
    if (kind.is_string() && kind.get<std::string>() == "composite")
      fail(part_where, "kind composite inside a composite (list its curves in this one instead)");
    parts.push_back(parse_curve(list[i], part_where, /*part=*/true));
  }
  return Curve::composite(std::move(id), std::move(parts));
}

// A curve object; `part`: one of a composite's curves, whose id is optional (POINTS.csv names the
// composite, not its parts).
Curve parse_curve(const json& entry, std::string& where, bool part) {
  if (!entry.is_object()) fail(where, "expected an object, found " + a_type_name(entry));

  std::string id;
  if (!part || entry.contains("id")) {
    const json& id_value = required_field(entry, "id", where);
    if (!id_value.is_string()) fail(where, "id: expected a string, found " + a_type_name(id_value));
    id = id_value.get<std::string>();
    if (id.empty()) fail(where, "id: empty");
    where += " (id " + quoted_excerpt(id) + ")";
    if (!id_fits_points_csv(id))
      fail(where, "id: must not contain commas, quotes, control characters or surrounding spaces "
                  "(POINTS.csv refers to curves by id)");
  }

  const json& kind_value = required_field(entry, "kind", where);
  if (!kind_value.is_string()) fail(where, "kind: expected a string, found " + a_type_name(kind_value));
  const std::string kind = kind_value.get<std::string>();

  if (kind == "bezier") {
    refuse_other_fields(entry, {"id", "kind", "points"}, "bezier", where);
    int dimension = 0;
    const auto points = point_list(entry, where, dimension);
    return dimension == 3 ? Curve::space_bezier(std::move(id), points) : Curve::bezier(std::move(id), plane_points(points));
  }
  if (kind == "rational_bezier") {
    refuse_other_fields(entry, {"id", "kind", "points", "weights"}, "rational_bezier", where);
    int dimension = 0;
    const auto points = point_list(entry, where, dimension);
    auto weights = number_list(entry, "weights", where);
    check_weights(weights, points, dimension, where);
    return dimension == 3 ? Curve::space_rational_bezier(std::move(id), points, weights)
                          : Curve::rational_bezier(std::move(id), plane_points(points), weights);
  }
  if (kind == "rational") {
    refuse_other_fields(entry, {"id", "kind", "x_num", "x_den", "y_num", "y_den", "z_num", "z_den"}, "rational", where);
    auto x_num = number_list(entry, "x_num", where);
    auto x_den = number_list(entry, "x_den", where);
    auto y_num = number_list(entry, "y_num", where);
    auto y_den = number_list(entry, "y_den", where);
    // A space curve has both z lists, a plane one neither.
    const bool has_z_num = entry.contains("z_num"), has_z_den = entry.contains("z_den");
    if (has_z_num != has_z_den) fail(where, std::string(has_z_num ? "z_den" : "z_num") + ": missing (a space curve has z_num and z_den)");
    std::vector<double> z_num, z_den;
    if (has_z_num) {
      z_num = number_list(entry, "z_num", where);
      z_den = number_list(entry, "z_den", where);
    }
    // Name the first list that disagrees with x_num: that is the field to fix.
    const std::pair<const char*, std::size_t> others[] = {{"x_den", x_den.size()}, {"y_num", y_num.size()},
                                                          {"y_den", y_den.size()}, {"z_num", has_z_num ? z_num.size() : x_num.size()},
                                                          {"z_den", has_z_num ? z_den.size() : x_num.size()}};
    for (const auto& [field, size] : others)
      if (size != x_num.size())
        fail(where, std::string(field) + ": " + std::to_string(size) + " coefficients, but x_num has " +
                        std::to_string(x_num.size()) + " (the lists need one common degree)");
    if (has_z_num)
      return Curve::space_rational(std::move(id), std::move(x_num), std::move(x_den), std::move(y_num), std::move(y_den),
                                   std::move(z_num), std::move(z_den));
    return Curve::rational(std::move(id), std::move(x_num), std::move(x_den), std::move(y_num), std::move(y_den));
  }
  if (kind == "matrix_weighted_bezier") {
    const MatrixWeightedCurve m = parse_matrix_weighted(entry, id, where);
    try {
      Curve converted = lowest_terms_curve(m, std::move(id));
      validate(converted);  // degree d n: a space curve of degree above 10 converts past kMaxDegree
      return converted;
    } catch (const CurveError& e) {
      std::string_view message(e.what());
      const std::string own_prefix = "curve " + quoted_excerpt(m.id) + ": ";
      if (message.starts_with(own_prefix)) message.remove_prefix(own_prefix.size());
      fail(where, std::string(message));
    }
  }
  if (kind == "nurbs") return parse_nurbs(entry, std::move(id), where);
  if (kind == "composite") return parse_composite(entry, std::move(id), where);
  fail(where, "kind: unknown " + quoted_excerpt(kind) +
                  " (expected bezier, rational_bezier, rational, matrix_weighted_bezier, nurbs or composite)");
}

}  // namespace

namespace {

// The text parsed (the SAX builder knows the path of every value, for messages) and its
// "curves" list checked; `path` names it in errors.
json parse_curves_text(std::string_view text, const std::string& path) {
  if (text.size() > kMaxCurvesBytes)
    fail(path, std::to_string(text.size()) + " bytes, more than " + std::to_string(kMaxCurvesBytes) +
                   " bytes, the limit for CURVES.json");
  LocatingBuilder builder(text);
  // strict: nothing may follow the top-level value.
  if (!json::sax_parse(text, &builder, json::input_format_t::json, /*strict=*/true)) {
    if (builder.error.empty()) builder.error = "malformed JSON";
    fail(path, builder.error);
  }
  json root = std::move(builder.root);
  if (!root.is_object()) fail(path, "expected an object {\"curves\": [...]}, found " + a_type_name(root));
  for (const auto& [key, value] : root.items())
    if (key != "curves") fail(path, quoted_excerpt(key) + ": unknown field (the top level has only \"curves\")");
  const auto list = root.find("curves");
  if (list == root.end()) fail(path, "curves: missing (expected {\"curves\": [...]})");
  if (!list->is_array()) fail(path, "curves: expected an array, found " + a_type_name(*list));
  if (list->empty()) fail(path, "curves: empty list (need at least one curve)");
  return root;
}

json parse_curves_file(const std::string& path) {
  return parse_curves_text(detail::read_whole_file(path, kMaxCurvesBytes, "CURVES.json"), path);
}

std::vector<Curve> curves_from_json(const json& root, const std::string& path) {
  const json& list = root["curves"];
  std::vector<Curve> curves;
  curves.reserve(list.size());
  std::unordered_map<std::string, std::size_t> index_of_id;
  for (std::size_t i = 0; i < list.size(); ++i) {
    std::string where = path + ": curves[" + std::to_string(i) + "]";
    Curve curve = parse_curve(list[i], where);
    const auto [previous, inserted] = index_of_id.emplace(curve.id, i);
    if (!inserted) fail(where, "id: duplicate of curves[" + std::to_string(previous->second) + "]");
    try {
      validate(curve);
    } catch (const CurveError& e) {
      // validate() names the curve itself ("curve \"a\": ..."); `where` already does.
      std::string_view message(e.what());
      const std::string own_prefix = "curve " + quoted_excerpt(curve.id) + ": ";
      if (message.starts_with(own_prefix)) message.remove_prefix(own_prefix.size());
      fail(where, std::string(message));
    }
    curves.push_back(std::move(curve));
  }
  return curves;
}

}  // namespace

std::vector<Curve> read_curves_json(const std::string& path) { return curves_from_json(parse_curves_file(path), path); }

std::vector<Curve> parse_curves_json(std::string_view text, const std::string& name) {
  return curves_from_json(parse_curves_text(text, name), name);
}

std::vector<std::optional<MatrixWeightedCurve>> detail::parse_matrix_weighted_json(std::string_view text,
                                                                                   const std::string& path) {
  const json root = parse_curves_text(text, path);
  const json& list = root["curves"];
  std::vector<std::optional<MatrixWeightedCurve>> out(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    const json& entry = list[i];
    const auto kind = entry.is_object() ? entry.find("kind") : entry.end();
    if (kind == entry.end() || !kind->is_string() || kind->get<std::string>() != "matrix_weighted_bezier") continue;
    std::string where = path + ": curves[" + std::to_string(i) + "]";
    const auto id = entry.find("id");
    if (id == entry.end() || !id->is_string()) fail(where, "id: expected a string");
    where += " (id " + quoted_excerpt(id->get<std::string>()) + ")";
    out[i] = parse_matrix_weighted(entry, id->get<std::string>(), where);
    try {
      convert(*out[i]);  // a singular M(t) is refused here as by read_curves_json
    } catch (const CurveError& e) {
      fail(where, e.what());
    }
  }
  return out;
}

std::vector<std::optional<MatrixWeightedCurve>> read_matrix_weighted_json(const std::string& path) {
  return detail::parse_matrix_weighted_json(detail::read_whole_file(path, kMaxCurvesBytes, "CURVES.json"), path);
}

}  // namespace bezinv
