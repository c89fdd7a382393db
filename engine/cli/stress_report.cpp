#include "stress_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace bezinv::cli {
namespace {

using datasets::StressRow;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string number(double x, const char* format = "%.3g") {
  char text[64];
  std::snprintf(text, sizeof text, format, x);
  return text;
}

std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else out += c;
  }
  return out;
}

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

// The curve in the CURVES.json schema, every coefficient exactly (nlohmann prints doubles so that
// they read back to the same bits). rational_bezier is written as `rational` with its four lists:
// its control points a_i = x_num_i / w_i would be rounded.
nlohmann::json curve_json(const Curve& curve) {
  const bool space = curve.dimension() == 3;
  if (curve.kind == CurveKind::bezier) {
    nlohmann::json points = nlohmann::json::array();
    for (std::size_t i = 0; i < curve.x_num.size(); ++i)
      points.push_back(space ? nlohmann::json{curve.x_num[i], curve.y_num[i], curve.z_num[i]}
                             : nlohmann::json{curve.x_num[i], curve.y_num[i]});
    return {{"id", "c"}, {"kind", "bezier"}, {"points", points}};
  }
  nlohmann::json out = {{"id", "c"},           {"kind", "rational"},   {"x_num", curve.x_num},
                        {"x_den", curve.x_den}, {"y_num", curve.y_num}, {"y_den", curve.y_den}};
  if (space) out["z_num"] = curve.z_num, out["z_den"] = curve.z_den;
  return out;
}

double ratio_of(const StressRow& row, const PointResult& got) {
  if (got.status != row.expected || !std::isfinite(got.t) || !std::isfinite(row.t_true)) return kNaN;
  return datasets::parameter_error(row, got) / row.bound;
}

// A bar chart of the histogram of log10(ratio).
std::string histogram_svg(const std::array<std::size_t, StressReport::kBins>& bins, std::size_t exact) {
  constexpr int kWidth = 460, kHeight = 170, kLeft = 40, kBottom = 30, kBar = (kWidth - kLeft - 10) / (StressReport::kBins + 1);
  std::size_t most = exact;
  for (std::size_t b : bins) most = std::max(most, b);
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
      << "\" role=\"img\"><title>histogram of log10(error / bound)</title>\n";
  const int plot = kHeight - kBottom - 10;
  auto bar = [&](int slot, std::size_t count, const char* colour, const std::string& label) {
    const int h = most ? static_cast<int>(std::lround(plot * static_cast<double>(count) / most)) : 0;
    const int x = kLeft + slot * kBar;
    svg << "<rect class=\"mark\" x=\"" << x << "\" y=\"" << (10 + plot - h) << "\" width=\"" << (kBar - 2)
        << "\" height=\"" << h << "\" fill=\"" << colour << "\"><title>" << escaped(label) << ": " << count
        << "</title></rect>\n";
  };
  bar(0, exact, "#7a7", "exact (error 0)");
  for (int b = 0; b < StressReport::kBins; ++b) {
    const double lo = StressReport::kFirstBin + b * StressReport::kBinWidth;
    bar(b + 1, bins[b], lo >= 0 ? "#c44" : "#47a", "log10 ratio in [" + number(lo) + ", " + number(lo + StressReport::kBinWidth) + ")");
  }
  svg << "<line x1=\"" << kLeft << "\" y1=\"" << (10 + plot) << "\" x2=\"" << (kWidth - 5) << "\" y2=\"" << (10 + plot)
      << "\" stroke=\"#333\"/>\n";
  for (int b = 0; b <= StressReport::kBins; b += 4) {
    const double lo = StressReport::kFirstBin + b * StressReport::kBinWidth;
    svg << "<text x=\"" << (kLeft + (b + 1) * kBar) << "\" y=\"" << (kHeight - 12) << "\" font-size=\"10\">" << number(lo)
        << "</text>\n";
  }
  svg << "<text x=\"" << kLeft << "\" y=\"" << (kHeight - 1) << "\" font-size=\"10\">exact | log10(|t - t_true| / bound): "
      << "right of 0 is beyond the model</text>\n";
  svg << "<text x=\"2\" y=\"14\" font-size=\"10\">" << most << "</text>\n</svg>\n";
  return svg.str();
}

// |t - t_true| against t_true, log scale (0 drawn at the bottom).
std::string scatter_svg(const std::vector<std::array<double, 2>>& points) {
  constexpr int kWidth = 460, kHeight = 170, kLeft = 40, kBottom = 25;
  double t_lo = 0, t_hi = 1, e_lo = -20, e_hi = -12;
  for (const auto& p : points) {
    t_lo = std::min(t_lo, p[0]);
    t_hi = std::max(t_hi, p[0]);
    if (p[1] > 0) e_hi = std::max(e_hi, std::ceil(std::log10(p[1])));
  }
  const int plot_w = kWidth - kLeft - 10, plot_h = kHeight - kBottom - 10;
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
      << "\" role=\"img\"><title>error against t</title>\n";
  svg << "<rect x=\"" << kLeft << "\" y=\"10\" width=\"" << plot_w << "\" height=\"" << plot_h
      << "\" fill=\"none\" stroke=\"#333\"/>\n";
  for (const auto& p : points) {
    const double e = p[1] > 0 ? std::clamp(std::log10(p[1]), e_lo, e_hi) : e_lo;
    const double x = kLeft + plot_w * (p[0] - t_lo) / (t_hi - t_lo), y = 10 + plot_h * (e_hi - e) / (e_hi - e_lo);
    svg << "<circle class=\"mark\" cx=\"" << number(x, "%.1f") << "\" cy=\"" << number(y, "%.1f")
        << "\" r=\"1.5\" fill=\"#47a\"/>\n";
  }
  svg << "<text x=\"" << kLeft << "\" y=\"" << (kHeight - 8) << "\" font-size=\"10\">t from " << number(t_lo) << " to "
      << number(t_hi) << "; |t - t_true| from 1e" << e_lo << " (and 0) to 1e" << e_hi << "</text>\n";
  svg << "<text x=\"2\" y=\"18\" font-size=\"10\">1e" << e_hi << "</text>\n";
  svg << "<text x=\"2\" y=\"" << (10 + plot_h) << "\" font-size=\"10\">1e" << e_lo << "</text>\n</svg>\n";
  return svg.str();
}

}  // namespace

void StressReport::Errors::add(double t_true, double error, double ratio, std::mt19937_64& rng) {
  ++compared;
  worst = std::max(worst, ratio);
  beyond += ratio > 1;
  far_beyond += ratio > 10;
  if (ratio == 0) {
    ++exact;
  } else {
    const int bin = static_cast<int>(std::floor((std::log10(ratio) - kFirstBin) / kBinWidth));
    ++histogram[std::clamp(bin, 0, kBins - 1)];
  }
  // A uniform sample of the compared rows (reservoir sampling).
  const std::array<double, 2> point{t_true, error};
  if (scatter.size() < kScatter) {
    scatter.push_back(point);
  } else {
    const std::size_t k = std::uniform_int_distribution<std::size_t>(0, compared - 1)(rng);
    if (k < kScatter) scatter[k] = point;
  }
}

void StressReport::add(const Origin& origin, const StressRow& row, const PointResult& got) {
  FamilyData& f = families_[origin.family];
  ++f.rows;
  const auto e = static_cast<std::size_t>(row.expected), g = static_cast<std::size_t>(got.status);
  if (e < datasets::kStatusCount && g < datasets::kStatusCount) ++f.confusion[e][g];
  const double ratio = ratio_of(row, got);
  if (!datasets::accepts(row, got.status)) {
    ++f.wrong;
    if (wrong_.size() < kWrongKept) wrong_.push_back({origin, *origin.curve, row, got, ratio});
    return;
  }
  if (std::isnan(ratio)) return;
  f.errors.add(row.t_true, ratio * row.bound, ratio, sample_rng_);
  if (f.worst.size() < kWorst || ratio > f.worst.back().ratio) {
    if (f.worst.size() == kWorst) f.worst.pop_back();
    f.worst.push_back({origin, *origin.curve, row, got, ratio});
    std::sort(f.worst.begin(), f.worst.end(), [](const Kept& a, const Kept& b) { return a.ratio > b.ratio; });
  }
}

void StressReport::add_baseline(datasets::Family family, const std::string& library, const StressRow& row,
                                double t) {
  BaselineData& b = baselines_[family][library];
  if (std::isnan(t)) {
    ++b.no_answer;
    return;
  }
  if (std::isnan(row.t_true)) return;
  double error = std::abs(t - row.t_true);
  if (row.expected == Status::double_point && std::isfinite(row.t2_true)) error = std::min(error, std::abs(t - row.t2_true));
  b.errors.add(row.t_true, error, error / row.bound, sample_rng_);
}

void StressReport::write(const std::filesystem::path& directory, const nlohmann::json& summary) const {
  std::error_code error;
  std::filesystem::create_directories(directory / "repro", error);
  if (error) throw std::runtime_error("cannot create " + (directory / "repro").string() + ": " + error.message());
  write_file(directory / "summary.json", summary.dump(2) + "\n");

  // The reproducers: every wrong row kept, then each family's worst.
  int next = 0;
  auto reproducer = [&](const Kept& k, const char* why) {
    const std::filesystem::path dir = directory / "repro" / std::to_string(next++);
    std::filesystem::create_directories(dir, error);
    if (error) throw std::runtime_error("cannot create " + dir.string() + ": " + error.message());
    write_file(dir / "curves.json", nlohmann::json{{"curves", nlohmann::json::array({curve_json(k.curve)})}}.dump(1) + "\n");
    char line[128];
    const bool space = k.curve.dimension() == 3;
    if (space)
      std::snprintf(line, sizeof line, "c,%.17g,%.17g,%.17g\n", k.row.point.x, k.row.point.y, k.row.z);
    else
      std::snprintf(line, sizeof line, "c,%.17g,%.17g\n", k.row.point.x, k.row.point.y);
    write_file(dir / "points.csv", std::string(space ? "curve,x,y,z\n" : "curve,x,y\n") + line);
    nlohmann::json acceptable = nlohmann::json::array();
    for (std::size_t s = 0; s < datasets::kStatusCount; ++s)
      if ((k.row.acceptable >> s) & 1u) acceptable.push_back(bezinv::to_string(static_cast<Status>(s)));
    auto finite = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
    const nlohmann::json truth = {
        {"why", why},
        {"family", datasets::to_string(k.origin.family)},
        {"kind", bezinv::to_string(k.origin.kind)},
        {"degree", k.origin.degree},
        {"path", k.origin.path},
        {"expected_status", bezinv::to_string(k.row.expected)},
        {"acceptable_statuses", acceptable},
        {"t_true", finite(k.row.t_true)},
        {"t2_true", finite(k.row.t2_true)},
        {"distance", finite(k.row.distance)},
        {"bound", finite(k.row.bound)},
        {"got_status", bezinv::to_string(k.got.status)},
        {"got_t", finite(k.got.t)},
        {"got_t2", finite(k.got.t2)},
        {"command", std::string("bezinv invert --curves curves.json --points points.csv --out out.csv") +
                        (std::string(k.origin.path) == "svd-only"     ? " --svd-only"
                         : std::string(k.origin.path) == "no-refine"  ? " --no-refine"
                         : std::string(k.origin.path) == "formula"    ? " --algebraic formula"
                         : std::string(k.origin.path) == "projection" ? " --off-curve projection"
                                                                      : "")}};
    write_file(dir / "truth.json", truth.dump(2) + "\n");
    return next - 1;
  };

  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html xmlns=\"http://www.w3.org/1999/xhtml\" lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n"
       << "<title>bezinv stress report</title>\n<style>\nbody{font-family:sans-serif;max-width:1000px;margin:2em auto;"
       << "color:#222}\ntable{border-collapse:collapse;margin:0.5em 0}\ntd,th{border:1px solid #bbb;padding:2px 6px;"
       << "text-align:right;font-size:13px}\n.bad{background:#fdd}\nsvg{margin-right:1em}\n</style>\n</head>\n<body>\n";
  html << "<h1>bezinv stress report</h1>\n<p>" << summary.value("rows", 0) << " rows, seed "
       << summary.value("seed", 0ULL) << ", tolerance " << number(summary.value("relative_tolerance", 0.0))
       << " &#215; diagonal. Truths: the nearest parameter of each double input, by 128-bit MPFR Newton. "
       << "<b>" << summary.value("wrong_status", 0) << "</b> wrong statuses. The bound is the accuracy model's "
       << "(docs/accuracy-model.md): a ratio above 1 is an error larger than rounding the input alone explains.</p>\n";
  html << "<table>\n<tr><th>family</th><th>rows</th><th>wrong status</th><th>t compared</th><th>exact</th>"
       << "<th>worst error / bound</th></tr>\n";
  for (const auto& [family, f] : families_) {
    html << "<tr" << (f.wrong ? " class=\"bad\"" : "") << "><td><a href=\"#" << datasets::to_string(family) << "\">"
         << datasets::to_string(family) << "</a></td><td>" << f.rows << "</td><td>" << f.wrong << "</td><td>" << f.errors.compared
         << "</td><td>" << f.errors.exact << "</td><td>" << (f.worst.empty() ? std::string("-") : number(f.worst.front().ratio))
         << "</td></tr>\n";
  }
  html << "</table>\n";

  // In a sentence, where the family's answers stand against the accuracy model and the contract.
  auto verdict = [](const FamilyData& f) {
    std::ostringstream out;
    out << f.rows << " rows, ";
    if (f.wrong == 0) out << "every status right. ";
    else out << "<b>" << f.wrong << " wrong statuses</b> (below). ";
    if (f.errors.compared == 0) {
      out << "No parameter compared.";
    } else if (f.errors.beyond == 0) {
      out << "Every one of the " << f.errors.compared << " parameters compared is within the accuracy model's bound (worst "
          << number(f.errors.worst) << " of it): as accurate as rounding the input allows.";
    } else {
      out << f.errors.beyond << " of the " << f.errors.compared << " parameters compared exceed the bound, "
          << f.errors.far_beyond << " of them by more than 10 times (worst " << number(f.errors.worst)
          << "): errors the rounding of the input alone does not explain (the worst rows below).";
    }
    return out.str();
  };
  for (const auto& [family, f] : families_) {
    html << "<h2 id=\"" << datasets::to_string(family) << "\">" << datasets::to_string(family) << "</h2>\n<p>"
         << verdict(f) << "</p>\n<p>bezinv</p>\n<div>\n"
         << histogram_svg(f.errors.histogram, f.errors.exact) << scatter_svg(f.errors.scatter) << "</div>\n";
    if (const auto it = baselines_.find(family); it != baselines_.end())
      for (const auto& [library, b] : it->second)
        html << "<p>" << library << " on the same rows (those whose truth is a point of the segment, kinds with one "
             << "denominator): " << b.errors.compared << " compared, worst error / bound " << number(b.errors.worst) << ", "
             << b.no_answer << " without an answer</p>\n<div>\n"
             << histogram_svg(b.errors.histogram, b.errors.exact) << scatter_svg(b.errors.scatter) << "</div>\n";
    html << "<table>\n<tr><th>expected \\ got</th>";
    for (std::size_t g = 0; g < datasets::kStatusCount; ++g) html << "<th>" << bezinv::to_string(static_cast<Status>(g)) << "</th>";
    html << "</tr>\n";
    for (std::size_t e = 0; e < datasets::kStatusCount; ++e) {
      std::size_t any = 0;
      for (std::size_t g = 0; g < datasets::kStatusCount; ++g) any += f.confusion[e][g];
      if (!any) continue;
      html << "<tr><th>" << bezinv::to_string(static_cast<Status>(e)) << "</th>";
      for (std::size_t g = 0; g < datasets::kStatusCount; ++g) html << "<td>" << f.confusion[e][g] << "</td>";
      html << "</tr>\n";
    }
    html << "</table>\n<p>Off the diagonal: rows within a margin of the tolerance (more than one status right) and "
         << "wrong statuses (" << f.wrong << ").</p>\n";
    html << "<table>\n<tr><th>worst rows</th><th>kind</th><th>degree</th><th>path</th><th>t_true</th><th>t</th>"
         << "<th>|t - t_true|</th><th>/ bound</th><th>reproducer</th></tr>\n";
    for (const Kept& k : f.worst) {
      const int n = reproducer(k, "among the family's largest errors over the bound");
      html << "<tr><td></td><td>" << bezinv::to_string(k.origin.kind) << "</td><td>" << k.origin.degree << "</td><td>"
           << k.origin.path << "</td><td>" << number(k.row.t_true, "%.17g") << "</td><td>" << number(k.got.t, "%.17g")
           << "</td><td>" << number(k.ratio * k.row.bound) << "</td><td>" << number(k.ratio) << "</td><td>repro/" << n
           << "</td></tr>\n";
    }
    html << "</table>\n";
  }
  if (!wrong_.empty()) {
    html << "<h2 id=\"wrong\">Wrong statuses</h2>\n<table>\n<tr><th>family</th><th>kind</th><th>degree</th><th>path</th>"
         << "<th>expected</th><th>got</th><th>reproducer</th></tr>\n";
    for (const Kept& k : wrong_) {
      const int n = reproducer(k, "a wrong status");
      html << "<tr class=\"bad\"><td>" << datasets::to_string(k.origin.family) << "</td><td>"
           << bezinv::to_string(k.origin.kind) << "</td><td>" << k.origin.degree << "</td><td>" << k.origin.path
           << "</td><td>" << bezinv::to_string(k.row.expected) << "</td><td>" << bezinv::to_string(k.got.status)
           << "</td><td>repro/" << n << "</td></tr>\n";
    }
    html << "</table>\n";
  }
  html << "<p>Each repro/N holds curves.json and points.csv, which <code>bezinv invert --curves curves.json --points "
       << "points.csv --out out.csv</code> runs as they are, and truth.json with the row's truth and what it got.</p>\n"
       << "</body>\n</html>\n";
  write_file(directory / "index.html", html.str());
}

}  // namespace bezinv::cli
