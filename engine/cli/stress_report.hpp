#pragma once
// `bezinv stress --report DIR`: one self-contained page (DIR/index.html: inline SVG, no script, no
// network), DIR/summary.json (the --json object), and DIR/repro/N/ for every wrong status and each
// family's worst rows: curves.json + points.csv that `bezinv invert` runs as they are, and
// truth.json with what the row should have been given.
#include <array>
#include <cstddef>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/datasets/stress.hpp"
#include "bezinv/invert.hpp"

namespace bezinv::cli {

class StressReport {
 public:
  // Where a row came from, for its reproducer and the tables.
  struct Origin {
    datasets::Family family;
    CurveKind kind;
    int degree;
    const char* path;
    const Curve* curve;
  };

  // Every row of the run, in any order.
  void add(const Origin& origin, const datasets::StressRow& row, const PointResult& got);
  // A baseline library's parameter for a row whose truth is a point of the segment (NaN: it gave
  // none), shown beside bezinv's in the family's section. For a double point either parameter is right.
  void add_baseline(datasets::Family family, const std::string& library, const datasets::StressRow& row, double t);
  // Writes the page, the summary and the reproducers into `directory` (created if needed; files of
  // these names are replaced, nothing else in it is touched). Throws std::runtime_error naming the
  // file that could not be written.
  void write(const std::filesystem::path& directory, const nlohmann::json& summary) const;

  // log10(|t - t_true| / bound) in bins of kBinWidth from kFirstBin; bin 0 also takes every smaller
  // ratio, the last every larger, and exact answers (|t - t_true| = 0) are counted apart.
  static constexpr double kFirstBin = -6.0, kBinWidth = 0.5;
  static constexpr int kBins = 20;

 private:
  struct Kept {  // a row kept for the tables and reproducers
    Origin origin;
    Curve curve;
    datasets::StressRow row;
    PointResult got;
    double ratio;  // |t - t_true| / bound, NaN where t is not compared
  };
  static constexpr std::size_t kScatter = 3000, kWorst = 8, kWrongKept = 40;
  // The errors of one source (bezinv, or a baseline) on one family: what its two plots show.
  struct Errors {
    std::array<std::size_t, kBins> histogram{};
    std::size_t exact = 0, compared = 0;
    std::size_t beyond = 0, far_beyond = 0;      // ratios above 1 and above 10
    double worst = 0;                            // the largest ratio
    std::vector<std::array<double, 2>> scatter;  // (t_true, |t - t_true|), a uniform sample
    void add(double t_true, double error, double ratio, std::mt19937_64& rng);
  };
  struct FamilyData {
    Errors errors;
    std::size_t rows = 0, wrong = 0;
    std::array<std::array<std::size_t, datasets::kStatusCount>, datasets::kStatusCount> confusion{};
    std::vector<Kept> worst;  // the rows of the largest ratios, at most kWorst
  };
  std::map<datasets::Family, FamilyData> families_;
  struct BaselineData {
    Errors errors;
    std::size_t no_answer = 0;
  };
  std::map<datasets::Family, std::map<std::string, BaselineData>> baselines_;
  std::vector<Kept> wrong_;
  std::mt19937_64 sample_rng_{12345};
};

}  // namespace bezinv::cli
