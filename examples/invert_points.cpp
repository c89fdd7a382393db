// Embedding bezinv: read curves, plan each once, invert a batch of points on the first curve.
//
//   invert_points CURVES.json
//
// CURVES.json is the file `bezinv invert --curves` reads (README "File formats"), e.g.
//   {"curves": [{"id": "arc", "kind": "rational_bezier",
//                "points": [[1, 0], [1, 1], [0, 1]], "weights": [1, 0.7071067811865476, 1]}]}
// Prints one line per point: the parameter t, the status and the distance to the curve.
#include <array>
#include <cstdio>
#include <exception>
#include <vector>

#include "bezinv/io.hpp"      // read_curves_json, InputError
#include "bezinv/invert.hpp"  // invert, Point, PointResult, Status, to_string
#include "bezinv/plan.hpp"    // make_plan

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s CURVES.json\n", argv[0]);
    return 2;
  }
  try {
    // Every curve of the file, validated (throws bezinv::InputError naming the file and field).
    const std::vector<bezinv::Curve> curves = bezinv::read_curves_json(argv[1]);
    const bezinv::Curve& curve = curves.front();  // the reader never returns an empty list

    // The plan holds everything computed once per curve (normalization, Bezout matrices);
    // build it once and invert as many points against it as you like.
    const bezinv::InversionPlan plan = bezinv::make_plan(curve);

    // Points with known parameters: Curve::point(t) evaluates the curve, so inverting these
    // should give t back with status `ok`.
    const std::array<double, 4> known_t = {0.0, 0.25, 0.5, 1.0};
    std::vector<bezinv::Point> points;
    for (double t : known_t) {
      const std::array<double, 2> p = curve.point(t);
      points.push_back({p[0], p[1]});
    }
    // And one point well away from the curve: status `off_curve`, with t the parameter of the
    // nearest point of the segment and the residual its distance.
    const std::array<double, 2> mid = curve.point(0.5);
    points.push_back({mid[0] + 10.0, mid[1] + 10.0});

    // One call for the whole span; results[i] answers points[i]. The default options use all
    // cores and a tolerance of 1e-6 x the curve's size (bezinv::InvertOptions to change them).
    std::vector<bezinv::PointResult> results(points.size());
    bezinv::invert(plan, points, results);

    std::printf("curve %s, degree %d\n", curve.id.c_str(), curve.degree());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const bezinv::PointResult& r = results[i];
      std::printf("point (%.6g, %.6g): t = %.12g  status = %s  residual = %.3g\n", points[i].x, points[i].y, r.t,
                  bezinv::to_string(r.status), r.residual);
    }
  } catch (const std::exception& e) {  // InputError, CurveError: one line saying what is wrong
    std::fprintf(stderr, "invert_points: %s\n", e.what());
    return 2;
  }
  return 0;
}
