// OUT.npy read back (bezinv merge): the writer's records (results.cpp), a chunk at a time.
#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "bezinv/io.hpp"
#include "io/npy.hpp"
#include "io/result_record.hpp"
#include "quote.hpp"

namespace bezinv {
namespace {

class NpyResultReader final : public ResultReader {
 public:
  explicit NpyResultReader(const std::string& path) : path_(path) {
    file_ = std::fopen(path.c_str(), "rb");
    if (file_ == nullptr) throw InputError(path + ": cannot read: " + std::strerror(errno));
    try {
      const detail::NpyHeader header = detail::read_npy_header(file_, path);
      if (header.descr == detail::kResultWithPointDescr)
        columns_.point = true;
      else if (header.descr != detail::kResultDescr)
        throw InputError(path + ": header: dtype " + detail::escaped_excerpt(header.descr) +
                         " is not that of bezinv's OUT.npy");
      record_bytes_ = detail::record_bytes_for(columns_);
      if (header.shape.size() != 1) throw InputError(path + ": header: shape " + detail::shape_text(header.shape) + " is not (N,)");
      rows_ = header.shape[0];
    } catch (...) {
      std::fclose(file_);
      throw;
    }
  }
  ~NpyResultReader() override { std::fclose(file_); }
  NpyResultReader(const NpyResultReader&) = delete;
  NpyResultReader& operator=(const NpyResultReader&) = delete;

  std::uint64_t rows() const override { return rows_; }
  ResultColumns columns() const override { return columns_; }

  std::size_t read(std::span<PointResult> results, std::span<Point3> at) override {
    std::size_t count = static_cast<std::size_t>(std::min<std::uint64_t>(results.size(), rows_ - done_));
    if (!at.empty()) count = std::min(count, at.size());
    if (count == 0) return 0;
    records_.resize(count * record_bytes_);
    detail::read_npy_data(file_, path_, records_.data(), records_.size());
    for (std::size_t i = 0; i < count; ++i) {
      const char* record = records_.data() + i * record_bytes_;
      if (!at.empty()) {
        double xyz[3] = {PointResult::nan, PointResult::nan, PointResult::nan};
        if (columns_.point) std::memcpy(xyz, record + detail::kRecordBytes, sizeof xyz);
        at[i] = Point3{xyz[0], xyz[1], xyz[2]};
      }
      double numbers[5];
      std::memcpy(numbers, record, sizeof numbers);
      PointResult& r = results[i];
      r = PointResult{};
      r.t = numbers[0], r.residual = numbers[1], r.t2 = numbers[2], r.sigma_min = numbers[3], r.sigma_next = numbers[4];
      const auto status = static_cast<unsigned char>(record[40]), path = static_cast<unsigned char>(record[41]);
      if (status > static_cast<unsigned char>(Status::failed) || path > static_cast<unsigned char>(Path::projection))
        throw InputError(path_ + ": row " + std::to_string(done_ + i) + ": status " + std::to_string(status) +
                         ", path " + std::to_string(path) + " are not bezinv's codes");
      r.status = static_cast<Status>(status);
      r.path = static_cast<Path>(path);
    }
    done_ += count;
    return count;
  }

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
  std::uint64_t rows_ = 0, done_ = 0;
  ResultColumns columns_;
  std::size_t record_bytes_ = detail::kRecordBytes;
  std::vector<char> records_;
};

}  // namespace

std::unique_ptr<ResultReader> open_results_npy(const std::string& path) {
  return std::make_unique<NpyResultReader>(path);
}

}  // namespace bezinv
