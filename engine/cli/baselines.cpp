#include "baselines.hpp"

#include <sys/resource.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#ifdef BEZINV_HAVE_OCCT
#include <Geom2dAPI_ProjectPointOnCurve.hxx>
#include <Geom2d_BezierCurve.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <gp_Pnt2d.hxx>
#endif

#ifdef BEZINV_HAVE_SISL
#include <sisl.h>
#endif

namespace bezinv::baselines {
namespace {

// Used by the projectors only: a build without either library has none (clang warns of it).
#if defined(BEZINV_HAVE_OCCT) || defined(BEZINV_HAVE_SISL)
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
#endif

#ifdef BEZINV_HAVE_OCCT
// Poles a_i = num_i / w_i (Curve stores rational_bezier as w_i a_i over w_i) and weights w_i.
class OcctProjector : public Projector {
 public:
  explicit OcctProjector(const Curve& curve) {
    const int n = curve.degree();
    TColgp_Array1OfPnt2d poles(1, n + 1);
    TColStd_Array1OfReal weights(1, n + 1);
    for (int i = 0; i <= n; ++i) {
      poles.SetValue(i + 1, gp_Pnt2d(curve.x_num[i] / curve.x_den[i], curve.y_num[i] / curve.y_den[i]));
      weights.SetValue(i + 1, curve.x_den[i]);
    }
    curve_ = new Geom2d_BezierCurve(poles, weights);
  }
  double parameter(Point point) const override {
    const Geom2dAPI_ProjectPointOnCurve projection(gp_Pnt2d(point.x, point.y), curve_);
    return projection.NbPoints() > 0 ? projection.LowerDistanceParameter() : kNaN;
  }

 private:
  Handle(Geom2d_Curve) curve_;
};
#endif

#ifdef BEZINV_HAVE_SISL
// SISL's geometric resolution for s1953: far below any error measured (curves of unit size).
constexpr double kSislGeometricResolution = 1e-9;

// A Bezier curve of degree n is the B-spline of order n+1 on the knots (0^{n+1}, 1^{n+1}); kind 2
// (rational B-spline) takes the coefficients in homogeneous form (w a_x, w a_y, w), which is how
// Curve stores a rational_bezier (x_num, y_num, x_den). newCurve copies the arrays (icopy = 1).
class SislProjector : public Projector {
 public:
  explicit SislProjector(const Curve& curve) {
    const int n = curve.degree();
    std::vector<double> knots(2 * (n + 1), 0.0);
    std::fill(knots.begin() + n + 1, knots.end(), 1.0);
    std::vector<double> coefficients;
    for (int i = 0; i <= n; ++i) coefficients.insert(coefficients.end(), {curve.x_num[i], curve.y_num[i], curve.x_den[i]});
    curve_ = newCurve(n + 1, n + 1, knots.data(), coefficients.data(), 2, 2, 1);
  }
  ~SislProjector() override { freeCurve(curve_); }
  SislProjector(const SislProjector&) = delete;
  SislProjector& operator=(const SislProjector&) = delete;

  // s1953 returns every parameter where the distance is locally closest (and curve pieces, for a
  // curve that runs along a circle around the point): the nearest of them, measured with s1221.
  double parameter(Point point) const override {
    double p[2] = {point.x, point.y};
    int count = 0, pieces = 0, status = 0;
    double* parameters = nullptr;
    SISLIntcurve** intersection_curves = nullptr;
    s1953(curve_, p, 2, 0.0, kSislGeometricResolution, &count, &parameters, &pieces, &intersection_curves, &status);
    double best = kNaN;
    if (status >= 0 && count == 1) {
      best = parameters[0];
    } else if (status >= 0) {
      double best_distance = std::numeric_limits<double>::infinity();
      for (int i = 0; i < count; ++i) {
        double value[2];
        int left = 0, evaluation_status = 0;
        s1221(curve_, 0, parameters[i], &left, value, &evaluation_status);
        const double distance = std::hypot(value[0] - point.x, value[1] - point.y);
        if (evaluation_status >= 0 && distance < best_distance) best_distance = distance, best = parameters[i];
      }
    }
    std::free(parameters);
    if (intersection_curves != nullptr) freeIntcrvlist(intersection_curves, pieces);
    return best;
  }

 private:
  SISLCurve* curve_ = nullptr;
};
#endif

}  // namespace

const char* to_string(Library library) { return library == Library::occt ? "occt" : "sisl"; }

bool available(Library library) {
#ifdef BEZINV_HAVE_OCCT
  if (library == Library::occt) return true;
#endif
#ifdef BEZINV_HAVE_SISL
  if (library == Library::sisl) return true;
#endif
  (void)library;
  return false;
}

std::unique_ptr<Projector> projector(Library library, const Curve& curve) {
  if (!curve.common_denominator()) return nullptr;
#ifdef BEZINV_HAVE_OCCT
  if (library == Library::occt) return std::make_unique<OcctProjector>(curve);
#endif
#ifdef BEZINV_HAVE_SISL
  if (library == Library::sisl) return std::make_unique<SislProjector>(curve);
#endif
  (void)library;
  return nullptr;
}

bool stack_is_large() {
  rlimit limit{};
  return getrlimit(RLIMIT_STACK, &limit) == 0 &&
         (limit.rlim_cur == RLIM_INFINITY || limit.rlim_cur >= (rlim_t{1} << 32));
}

}  // namespace bezinv::baselines
