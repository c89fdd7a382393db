// POINTS.npy (+ the curve of every point: --curve or a --curve-index .npy) -> PointRow chunks.
//
// The arrays are read a chunk at a time straight into place (fread of raw little-endian doubles),
// so a .npy input costs no parsing at all. Everything the header promises is checked before the
// first chunk: dtype, order, shape, the data length against the file size, and the index array's
// length against the points'.
#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include "bezinv/io.hpp"
#include "io/npy.hpp"
#include "io/point_readers.hpp"
#include "quote.hpp"

namespace bezinv {
namespace {

using namespace detail;

// The arrays are copied byte for byte: the host must store doubles and integers as '<' does.
static_assert(std::endian::native == std::endian::little, "the .npy readers assume a little-endian host");

std::string decimal(unsigned __int128 value) {
  std::string digits;
  do {
    digits.insert(digits.begin(), static_cast<char>('0' + static_cast<int>(value % 10)));
    value /= 10;
  } while (value != 0);
  return digits;
}

// An open .npy file, its header read and the file positioned at the data.
class NpyFile {
 public:
  explicit NpyFile(const std::string& path) : path_(path) {
    file_ = std::fopen(path.c_str(), "rb");
    if (file_ == nullptr) throw InputError(path + ": cannot read: " + std::strerror(errno));
    try {
      header_ = read_npy_header(file_, path);
    } catch (...) {
      std::fclose(file_);
      throw;
    }
  }
  ~NpyFile() { std::fclose(file_); }
  NpyFile(const NpyFile&) = delete;
  NpyFile& operator=(const NpyFile&) = delete;

  const NpyHeader& header() const { return header_; }
  std::FILE* file() const { return file_; }
  const std::string& path() const { return path_; }

  // The data of `rows` rows of `row_bytes` each, in bytes. The file must hold exactly that after
  // the header (checked when the size is known: a regular file; a pipe is checked as it is read).
  // The shape comes from the file, so the product is computed in 128 bits: shape (2^60, 2) must
  // be refused for its size, not wrap around to a small one.
  std::uint64_t expect_data(std::uint64_t rows, std::uint64_t row_bytes) const {
    const unsigned __int128 needed = static_cast<unsigned __int128>(rows) * row_bytes;
    const std::string needs = "shape " + shape_text(header_.shape) + " needs " + decimal(needed) + " bytes after the header";
    std::error_code no_size;
    const bool regular = std::filesystem::is_regular_file(path_, no_size);
    const std::uintmax_t size = regular ? std::filesystem::file_size(path_, no_size) : 0;
    const bool known = regular && !no_size;
    const std::uint64_t found = known && size >= header_.data_offset ? size - header_.data_offset : 0;
    if (needed > std::numeric_limits<std::uint64_t>::max() - header_.data_offset)
      throw InputError(path_ + ": data: " + needs + (known ? ", the file has " + std::to_string(found) : ", more than any file holds"));
    const std::uint64_t bytes = static_cast<std::uint64_t>(needed);
    if (!known) return bytes;
    if (found < bytes) throw InputError(path_ + ": data: truncated: " + needs + ", the file has " + std::to_string(found));
    if (found > bytes)
      throw InputError(path_ + ": data: " + std::to_string(found - bytes) + " bytes after the end of the " +
                       shape_text(header_.shape) + " array");
    return bytes;
  }

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
  NpyHeader header_;
};

class NpyPointReader final : public PointReader {
 public:
  NpyPointReader(const std::string& path, const std::vector<Curve>& curves, const CurveSelection& selection)
      : points_(path), curve_count_(curves.size()) {
    const NpyHeader& header = points_.header();
    if (header.descr != "'<f8'") fail_npy_header(path, "dtype " + escaped_excerpt(header.descr) + " is not '<f8' (float64)");
    if (header.fortran_order) fail_npy_header(path, "fortran_order is True; only C order is read");
    if (header.shape.size() != 2 || (header.shape[1] != 2 && header.shape[1] != 3))
      fail_npy_header(path, "shape " + shape_text(header.shape) + " is not (N, 2) or (N, 3)");
    width_ = static_cast<std::size_t>(header.shape[1]);
    const std::uint64_t rows = header.shape[0];
    progress_.bytes_total = header.data_offset + points_.expect_data(rows, 8 * width_);
    // --rows: [begin, end) of the file's rows.
    if (selection.begin > rows || selection.begin > selection.end)
      throw InputError(path + ": --rows " + std::to_string(selection.begin) + ":" +
                       (selection.end == UINT64_MAX ? std::string() : std::to_string(selection.end)) +
                       ": the file has " + std::to_string(rows) + " points");
    first_ = selection.begin;
    total_ = std::min(selection.end, rows) - first_;
    progress_.points_total = total_;
    for (const Curve& c : curves) space_.push_back(c.dimension() == 3);

    if (!selection.curve.empty() && !selection.index_path.empty())
      throw InputError(path + ": give --curve or --curve-index, not both");
    if (!selection.curve.empty()) {
      curve_ = selected_curve(path, curves, selection.curve);
      check_width(path + ": header", shape_text(header.shape), width_, curves[static_cast<std::size_t>(curve_)]);
    } else if (!selection.index_path.empty()) {
      indices_ = std::make_unique<NpyFile>(selection.index_path);
      const NpyHeader& index_header = indices_->header();
      const std::string& index_path = selection.index_path;
      if (index_header.descr == "'<i4'") index_bytes_ = 4;
      else if (index_header.descr == "'<i8'") index_bytes_ = 8;
      else fail_npy_header(index_path, "dtype " + escaped_excerpt(index_header.descr) + " is not '<i4' or '<i8' (int32, int64)");
      // A 1-D array is the same in either order.
      if (index_header.shape.size() != 1) fail_npy_header(index_path, "shape " + shape_text(index_header.shape) + " is not (N,)");
      if (index_header.shape[0] != rows)
        fail_npy_header(index_path, "shape " + shape_text(index_header.shape) + " does not match the " +
                                    std::to_string(rows) + " points of " + path);
      indices_->expect_data(rows, index_bytes_);
    } else {
      throw InputError(path + ": a .npy of points needs --curve ID or --curve-index FILE.npy to name the curves");
    }
    if (first_ > 0) {
      skip(points_, first_ * 8 * width_);
      if (indices_) skip(*indices_, first_ * index_bytes_);
    }
  }

  std::size_t read(std::span<PointRow> rows) override {
    const std::size_t count = static_cast<std::size_t>(std::min<std::uint64_t>(rows.size(), total_ - progress_.points));
    if (count == 0) return 0;
    coordinates_.resize(width_ * count);
    read_npy_data(points_.file(), points_.path(), coordinates_.data(), coordinates_.size() * sizeof(double));
    if (indices_) {
      index_buffer_.resize(count * index_bytes_);
      read_npy_data(indices_->file(), indices_->path(), index_buffer_.data(), index_buffer_.size());
    }
    for (std::size_t i = 0; i < count; ++i) {
      const char* reason = "";
      const int curve = indices_ ? curve_at(i, reason) : curve_;
      make_point_row(rows[i], &coordinates_[width_ * i], width_, curve, reason, space_);
    }
    progress_.points += count;
    progress_.bytes = points_.header().data_offset + (first_ + progress_.points) * 8 * width_;
    return count;
  }

  ReadProgress progress() const override { return progress_; }

 private:
  // Moves past `bytes` of the data: a seek in a regular file, reading them in a pipe.
  static void skip(const NpyFile& file, std::uint64_t bytes) {
    if (fseeko(file.file(), static_cast<off_t>(bytes), SEEK_CUR) == 0) return;
    std::vector<unsigned char> buffer(1 << 16);
    while (bytes > 0) {
      const std::size_t step = static_cast<std::size_t>(std::min<std::uint64_t>(bytes, buffer.size()));
      read_npy_data(file.file(), file.path(), buffer.data(), step);
      bytes -= step;
    }
  }

  int curve_at(std::size_t i, const char*& reason) const {
    std::int64_t index = 0;
    if (index_bytes_ == 4) {
      std::int32_t narrow = 0;
      std::memcpy(&narrow, index_buffer_.data() + 4 * i, 4);
      index = narrow;
    } else {
      std::memcpy(&index, index_buffer_.data() + 8 * i, 8);
    }
    return curve_from_index(index, curve_count_, reason);
  }

  NpyFile points_;
  std::size_t curve_count_;
  std::uint64_t total_ = 0;          // rows read: the --rows range's, else the file's
  std::uint64_t first_ = 0;          // the first of them
  std::size_t width_ = 2;             // 2 (x, y) or 3 (x, y, z) doubles a row
  std::vector<bool> space_;           // curve i is a space curve
  int curve_ = -1;                    // --curve
  std::unique_ptr<NpyFile> indices_;  // --curve-index
  std::size_t index_bytes_ = 0;
  std::vector<double> coordinates_;
  std::vector<unsigned char> index_buffer_;
  ReadProgress progress_;
};

}  // namespace

std::uint64_t npy_rows(const std::string& path) {
  const NpyFile file(path);
  if (file.header().shape.size() != 2) fail_npy_header(path, "shape " + shape_text(file.header().shape) + " is not (N, 2) or (N, 3)");
  return file.header().shape[0];
}

namespace detail {

int selected_curve(const std::string& path, const std::vector<Curve>& curves, const std::string& selection,
                   const char* option) {
  for (std::size_t i = 0; i < curves.size(); ++i)
    if (curves[i].id == selection) return static_cast<int>(i);
  const bool digits = std::all_of(selection.begin(), selection.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (digits && selection.size() < 10) {
    const std::size_t index = std::stoul(selection);
    if (index < curves.size()) return static_cast<int>(index);
  }
  throw InputError(path + ": " + option + " '" + selection + "': no curve has this id, nor is it an index below " +
                   std::to_string(curves.size()));
}

void check_width(const std::string& where, const std::string& shape, std::size_t width, const Curve& curve) {
  const int dimension = curve.dimension();
  if (static_cast<int>(width) != dimension)
    throw InputError(where + ": shape " + shape + ": curve " + quoted_excerpt(curve.id) + " is a " +
                     (dimension == 3 ? "space curve, whose points are (N, 3)" : "plane curve, whose points are (N, 2)"));
}

std::unique_ptr<PointReader> open_points_npy(const std::string& path, const std::vector<Curve>& curves,
                                             const CurveSelection& selection) {
  return std::make_unique<NpyPointReader>(path, curves, selection);
}

}  // namespace detail
}  // namespace bezinv
