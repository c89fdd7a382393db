#pragma once
// `bezinv formula`: per curve, the inversion formula t = N(x, y) / M(x, y) (Wang & Joe), the centre
// of its pencil (degree 1 formulae), the implicit equation, and the formula's base points on the
// curve with the curve's singular points among them.
#include <string>
#include <vector>

namespace bezinv::cli {

struct FormulaOptions {
  std::string curves_path;
  std::string curve_id;                 // empty: every curve
  std::vector<double> base_parameters;  // FormulaChoice::base_parameters (a conic's centre, ...)
  bool json = false;
};

// "inf" or a number per item, comma-separated; throws std::invalid_argument naming the item.
std::vector<double> parse_base_parameters(const std::string& list);

// Prints every curve's formula (one JSON object with --json). A curve with no formula (not
// faithfully parametrized, past the degree limit) gets its reason in place of the formula.
// Returns the exit code.
int run_formula(const FormulaOptions& options);

}  // namespace bezinv::cli
