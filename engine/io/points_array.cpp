// Points held in memory (bezinv/io.hpp PointArray) -> PointRow chunks, checked row by row as a
// POINTS.npy's rows are, so that an array and the same .npy file get the same answers.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bezinv/io.hpp"
#include "io/point_readers.hpp"

namespace bezinv {
namespace {

using namespace detail;

class ArrayPointReader final : public PointReader {
 public:
  ArrayPointReader(const PointArray& points, const std::vector<Curve>& curves)
      : points_(points), curve_count_(curves.size()) {
    const std::string& name = points.name;
    if (points.width != 2 && points.width != 3)
      throw InputError(name + ": " + std::to_string(points.width) + " coordinates a row, not 2 (x, y) or 3 (x, y, z)");
    if (points.coordinates.size() % points.width != 0)
      throw InputError(name + ": " + std::to_string(points.coordinates.size()) + " numbers are not rows of " +
                       std::to_string(points.width));
    rows_ = points.coordinates.size() / points.width;
    progress_.points_total = rows_;
    progress_.bytes_total = points.coordinates.size() * sizeof(double);
    for (const Curve& c : curves) space_.push_back(c.dimension() == 3);
    // Appended, not "(" + ...: GCC 12 warns falsely (-Wrestrict) on a literal plus a temporary string.
    std::string shape = "(";
    shape += std::to_string(rows_) + ", " + std::to_string(points.width) + ")";
    if (!points.curve.empty() && !points.curve_index.empty())
      throw InputError(name + ": give the curve or a curve index per row, not both");
    if (!points.curve.empty()) {
      curve_ = selected_curve(name, curves, points.curve, "curve");
      check_width(name, shape, points.width, curves[static_cast<std::size_t>(curve_)]);
    } else if (points.curve_index.empty() && rows_ > 0) {
      throw InputError(name + ": name the curve, or give a curve index per row");
    } else if (points.curve_index.size() != rows_) {
      throw InputError(name + ": curve_index: " + std::to_string(points.curve_index.size()) + " indices for " +
                       std::to_string(rows_) + " points");
    }
  }

  std::size_t read(std::span<PointRow> rows) override {
    const std::size_t begin = static_cast<std::size_t>(progress_.points);
    const std::size_t count = std::min(rows.size(), rows_ - begin);
    const std::size_t width = points_.width;
    for (std::size_t i = 0; i < count; ++i) {
      const char* reason = "";
      const int curve = curve_ >= 0 ? curve_ : curve_from_index(points_.curve_index[begin + i], curve_count_, reason);
      make_point_row(rows[i], &points_.coordinates[width * (begin + i)], width, curve, reason, space_);
    }
    progress_.points += count;
    progress_.bytes = progress_.points * width * sizeof(double);
    return count;
  }

  ReadProgress progress() const override { return progress_; }

 private:
  PointArray points_;
  std::size_t curve_count_;
  std::size_t rows_ = 0;
  std::vector<bool> space_;
  int curve_ = -1;
  ReadProgress progress_;
};

}  // namespace

std::unique_ptr<PointReader> open_points(const PointArray& points, const std::vector<Curve>& curves) {
  return std::make_unique<ArrayPointReader>(points, curves);
}

}  // namespace bezinv
