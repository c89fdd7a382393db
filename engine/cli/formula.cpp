#include "formula.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "bezinv/implicit_equation.hpp"
#include "bezinv/inversion_formula.hpp"
#include "bezinv/io.hpp"
#include "bezinv/singular_points.hpp"

namespace bezinv::cli {
namespace {

using Json = nlohmann::ordered_json;

double largest_monomial(const PlanePolynomial& p) {
  double largest = 0.0;
  for (double c : p.monomials()) largest = std::max(largest, std::abs(c));
  return largest;
}

// A polynomial's monomials divided by `scale`, as text, largest total degree first:
// "1225 y^3 - 756 x^2 y + ...". Coefficients below 1e-12 of the largest are rounding of terms
// that are not there.
std::string monomial_text(const PlanePolynomial& p, double scale) {
  std::vector<double> a = p.monomials();
  for (double& c : a) c /= scale;
  double largest = 0.0;
  for (double c : a) largest = std::max(largest, std::abs(c));
  std::string out;
  for (int k = p.degree(); k >= 0; --k)
    for (int j = k; j >= 0; --j) {
      const int i = k - j;
      const double c = a[static_cast<std::size_t>(PlanePolynomial::index(i, j))];
      if (!(std::abs(c) > 1e-12 * largest)) continue;
      char number[64];
      std::snprintf(number, sizeof number, "%.12g", std::abs(c));
      std::string term;
      if (i > 0) term += i == 1 ? "x" : "x^" + std::to_string(i);
      if (j > 0) term += std::string(term.empty() ? "" : " ") + (j == 1 ? "y" : "y^" + std::to_string(j));
      const bool unit = term.size() > 0 && std::string(number) == "1";
      out += out.empty() ? (c < 0 ? "-" : "") : (c < 0 ? " - " : " + ");
      out += unit ? term : (term.empty() ? std::string(number) : std::string(number) + " " + term);
    }
  return out.empty() ? "0" : out;
}

Json monomial_json(const PlanePolynomial& p) {
  const std::vector<double> a = p.monomials();
  Json terms = Json::array();
  for (int k = p.degree(); k >= 0; --k)
    for (int j = k; j >= 0; --j) {
      const double c = a[static_cast<std::size_t>(PlanePolynomial::index(k - j, j))];
      if (c != 0.0) terms.push_back({k - j, j, c});
    }
  return terms;
}

Json chebyshev_json(const PlanePolynomial& p) {
  const PlaneFrame& f = p.frame();
  return {{"frame",
           {{"centre", {f.centre[0], f.centre[1]}},
            {"scale", {f.scale_u, f.scale_v}},
            {"rotation", {f.cos_rotation, f.sin_rotation}}}},
          {"coefficients", std::vector<double>(p.coefficients().begin(), p.coefficients().end())}};
}

Json polynomial_json(const PlanePolynomial& p) {
  return {{"degree", p.degree()}, {"monomials", monomial_json(p)}, {"chebyshev", chebyshev_json(p)}};
}

std::string parameter_text(std::complex<double> t) {
  char text[96];
  if (std::isinf(t.real())) return "infinity";
  if (t.imag() == 0.0)
    std::snprintf(text, sizeof text, "%.15g", t.real());
  else
    std::snprintf(text, sizeof text, "%.15g %c %.15gi", t.real(), t.imag() < 0 ? '-' : '+', std::abs(t.imag()));
  return text;
}

Json parameter_json(std::complex<double> t) {
  if (std::isinf(t.real())) return "infinity";
  return Json::array({t.real(), t.imag()});
}

struct CurveFormula {
  const Curve* curve;
  std::optional<InversionFormula> formula;
  std::string formula_error;
  std::optional<ImplicitEquation> implicit;
  std::string implicit_error;
  std::optional<BasePoints> base;
  std::string base_error;
};

CurveFormula compute(const Curve& curve, const FormulaChoice& choice) {
  CurveFormula out{&curve, {}, {}, {}, {}, {}, {}};
  const InversionPlan plan = make_plan(curve);
  try {
    out.formula.emplace(plan, choice);
  } catch (const FormulaError& e) {
    out.formula_error = e.what();
  }
  try {
    out.implicit = implicit_equation(plan);
  } catch (const FormulaError& e) {
    out.implicit_error = e.what();
  }
  if (out.formula) try {
      out.base = base_points(plan, *out.formula);
    } catch (const FormulaError& e) {
      out.base_error = e.what();
    }
  return out;
}

void print_text(const CurveFormula& r) {
  const Curve& c = *r.curve;
  std::printf("curve \"%s\" (%s, degree %d)\n", c.id.c_str(), to_string(c.kind), c.degree());
  if (!r.formula) {
    std::printf("  %s\n", r.formula_error.c_str());
  } else {
    const InversionFormula& f = *r.formula;
    std::printf("  inversion formula t = N(x, y) / M(x, y), N and M of degree %d (the curve's degree %d)\n", f.degree(),
                f.curve_degree());
    // One factor for both (t is their ratio): the largest coefficient 1.
    const double scale = std::max(largest_monomial(f.numerator()), largest_monomial(f.denominator()));
    std::printf("    N = %s\n", monomial_text(f.numerator(), scale).c_str());
    std::printf("    M = %s\n", monomial_text(f.denominator(), scale).c_str());
    if (const auto centre = f.centre()) {
      if ((*centre)[2] != 0.0)
        std::printf("  centre of the pencil: (%.15g, %.15g)\n", (*centre)[0], (*centre)[1]);
      else
        std::printf("  centre of the pencil: at infinity, direction (%.15g, %.15g)\n", (*centre)[0], (*centre)[1]);
    }
    std::printf("  evidence: null ratio %.2g, next ratio %.2g, max |N/M - t| on the segment %.2g\n", f.null_ratio(),
                f.next_ratio(), f.segment_error());
  }
  if (r.implicit)
    std::printf("  implicit equation F(x, y) = 0 (det B up to a factor), degree %d:\n    F = %s\n", r.implicit->F.degree(),
                monomial_text(r.implicit->F, largest_monomial(r.implicit->F)).c_str());
  else
    std::printf("  %s\n", r.implicit_error.c_str());
  if (r.base) {
    std::printf("  base points on the curve (N = M = 0): %zu real", r.base->points.size());
    if (r.base->complex_points > 0) std::printf(", %d complex", r.base->complex_points);
    if (r.base->at_infinity) std::printf(", one at infinity");
    std::printf("\n");
    for (const BasePoint& p : r.base->points) {
      std::printf("    %-15s (%.15g, %.15g) at t =", to_string(p.kind), p.point[0], p.point[1]);
      for (std::size_t k = 0; k < p.parameters.size(); ++k)
        std::printf("%s %s", k ? "," : "", parameter_text(p.parameters[k]).c_str());
      std::printf("\n");
    }
  } else if (!r.base_error.empty()) {
    std::printf("  %s\n", r.base_error.c_str());
  }
  std::printf("\n");
}

Json to_json(const CurveFormula& r) {
  const Curve& c = *r.curve;
  Json out{{"id", c.id}, {"kind", to_string(c.kind)}, {"degree", c.degree()}};
  if (r.formula) {
    const InversionFormula& f = *r.formula;
    Json centre = nullptr;
    if (const auto h = f.centre()) centre = {(*h)[0], (*h)[1], (*h)[2]};
    out["formula"] = {{"curve_degree", f.curve_degree()},
                      {"degree", f.degree()},
                      {"N", polynomial_json(f.numerator())},
                      {"M", polynomial_json(f.denominator())},
                      {"centre", centre},
                      {"null_ratio", f.null_ratio()},
                      {"next_ratio", f.next_ratio()},
                      {"segment_error", f.segment_error()}};
  } else {
    out["formula"] = {{"error", r.formula_error}};
  }
  if (r.implicit)
    out["implicit"] = {{"F", polynomial_json(r.implicit->F)},
                       {"null_ratio", r.implicit->null_ratio},
                       {"next_ratio", r.implicit->next_ratio}};
  else
    out["implicit"] = {{"error", r.implicit_error}};
  if (r.base) {
    Json points = Json::array();
    for (const BasePoint& p : r.base->points) {
      Json parameters = Json::array();
      for (const auto t : p.parameters) parameters.push_back(parameter_json(t));
      points.push_back({{"kind", to_string(p.kind)}, {"point", {p.point[0], p.point[1]}}, {"parameters", parameters}});
    }
    out["base_points"] = {{"real", points},
                          {"complex", r.base->complex_points},
                          {"at_infinity", r.base->at_infinity}};
  } else {
    out["base_points"] = {{"error", r.base_error.empty() ? r.formula_error : r.base_error}};
  }
  return out;
}

}  // namespace

std::vector<double> parse_base_parameters(const std::string& list) {
  std::vector<double> out;
  std::size_t start = 0;
  while (start <= list.size() && !list.empty()) {
    const std::size_t end = std::min(list.find(',', start), list.size());
    const std::string item = list.substr(start, end - start);
    if (item == "inf" || item == "infinity") {
      out.push_back(std::numeric_limits<double>::infinity());
    } else {
      std::size_t used = 0;
      double value = 0.0;
      try {
        value = std::stod(item, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != item.size() || item.empty() || !std::isfinite(value))
        throw std::invalid_argument("--base-points: '" + item + "' is not a parameter (a finite number or inf)");
      out.push_back(value);
    }
    start = end + 1;
  }
  return out;
}

int run_formula(const FormulaOptions& options) {
  const std::vector<Curve> curves = read_curves_json(options.curves_path);
  FormulaChoice choice;
  choice.base_parameters = options.base_parameters;
  Json all = Json::array();
  bool found = false;
  for (const Curve& curve : curves) {
    if (!options.curve_id.empty() && curve.id != options.curve_id) continue;
    found = true;
    const CurveFormula r = compute(curve, choice);
    if (options.json)
      all.push_back(to_json(r));
    else
      print_text(r);
  }
  if (!found) throw std::invalid_argument(options.curves_path + ": no curve with id \"" + options.curve_id + "\"");
  if (options.json) std::printf("%s\n", Json{{"curves", all}}.dump().c_str());
  return 0;
}

}  // namespace bezinv::cli
