// PointResult chunks -> OUT.csv or OUT.npy (formats in bezinv/io.hpp), through an OutputTarget
// that publishes them only at commit (io/output_target.hpp).
#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "bezinv/io.hpp"
#include "io/npy.hpp"
#include "io/result_record.hpp"
#include "io/output_target.hpp"

namespace bezinv {
namespace {

using detail::OutputTarget;

constexpr std::string_view kHeader = "t,status,residual,t2,sigma_min,sigma_next,path,reason";
constexpr std::string_view kPointHeader = ",x_t,y_t,z_t";

// Rows formatted by one task: about 0.5 MB of text, enough to amortize the task, small enough
// that a group of them in flight stays in the tens of MB.
constexpr std::size_t kRowsPerBlock = 4096;
constexpr std::size_t kBlocksPerGroup = 32;

// Shortest text that reads back as the same double (std::to_chars without a precision), so
// round-trip precision in fewer bytes than %.17g. NaN (absent) is written "nan" whatever its
// sign bit, so readers need to know one spelling.
void append_number(std::string& out, double value) {
  if (std::isnan(value)) {
    out += "nan";
    return;
  }
  char digits[32];
  const auto [end, error] = std::to_chars(digits, digits + sizeof digits, value);
  (void)error;  // 32 bytes hold any shortest double ("-2.2250738585072014e-308" is 24)
  out.append(digits, end);
}

// Reasons are static text without commas; should one ever gain a comma, quote or line break,
// RFC 4180 quoting keeps the row's column count right.
void append_text_field(std::string& out, const char* text) {
  if (text == nullptr) return;
  const std::string_view field(text);
  if (field.find_first_of(",\"\r\n") == std::string_view::npos) {
    out += field;
    return;
  }
  out += '"';
  for (char c : field) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
}

void append_row(std::string& out, const PointResult& result) {
  append_number(out, result.t);
  out += ',';
  out += to_string(result.status);
  out += ',';
  append_number(out, result.residual);
  out += ',';
  append_number(out, result.t2);
  out += ',';
  append_number(out, result.sigma_min);
  out += ',';
  append_number(out, result.sigma_next);
  out += ',';
  out += to_string(result.path);
  out += ',';
  append_text_field(out, result.reason);
}

void append_point(std::string& out, const Point3& at) {
  for (const double v : {at.x, at.y, at.z}) {
    out += ',';
    append_number(out, v);
  }
}

class CsvResultWriter final : public ResultWriter {
 public:
  CsvResultWriter(const std::string& path, int threads, ResultColumns columns)
      : output_(path, false), arena_(threads > 0 ? threads : tbb::task_arena::automatic), blocks_(kBlocksPerGroup),
        columns_(columns) {
    output_.write(std::string(kHeader) + (columns.point ? std::string(kPointHeader) : "") + "\n");
  }

  ResultColumns columns() const override { return columns_; }
  void write(std::span<const PointResult> results) override { write_with_points(results, {}); }

  // Blocks of rows are formatted in parallel, a group at a time, and written in order.
  void write_with_points(std::span<const PointResult> results, std::span<const Point3> at) override {
    for (std::size_t group = 0; group < results.size(); group += kRowsPerBlock * kBlocksPerGroup) {
      const std::span<const PointResult> rows = results.subspan(group, std::min(results.size() - group, kRowsPerBlock * kBlocksPerGroup));
      const std::size_t blocks = (rows.size() + kRowsPerBlock - 1) / kRowsPerBlock;
      const auto format = [&](std::size_t b) {
        std::string& text = blocks_[b];
        text.clear();
        const std::size_t first = group + b * kRowsPerBlock, end = group + std::min(rows.size(), (b + 1) * kRowsPerBlock);
        for (std::size_t i = first; i < end; ++i) {
          append_row(text, results[i]);
          if (columns_.point) append_point(text, detail::point_or_nan(at, i));
          text += '\n';
        }
      };
      if (blocks == 1) format(0);
      else arena_.execute([&] { tbb::parallel_for(std::size_t{0}, blocks, format); });
      for (std::size_t b = 0; b < blocks; ++b) output_.write(blocks_[b]);
    }
  }

  void commit() override { output_.commit(); }

 private:
  OutputTarget output_;
  tbb::task_arena arena_;
  std::vector<std::string> blocks_;
  ResultColumns columns_;
};

using detail::kRecordBytes;
using detail::kResultDescr;

class NpyResultWriter final : public ResultWriter {
 public:
  NpyResultWriter(const std::string& path, ResultColumns columns)
      : output_(path, true), columns_(columns), descr_(detail::result_descr_for(columns)),
        record_bytes_(detail::record_bytes_for(columns)) {
    // The count is not known yet (a CSV input is not counted ahead): a placeholder of the same
    // length, rewritten at commit.
    output_.write(detail::npy_preamble(descr_, 0));
  }

  ResultColumns columns() const override { return columns_; }
  void write(std::span<const PointResult> results) override { write_with_points(results, {}); }

  void write_with_points(std::span<const PointResult> results, std::span<const Point3> at) override {
    records_.resize(results.size() * record_bytes_);
    char* record = records_.data();
    for (std::size_t i = 0; i < results.size(); ++i, record += record_bytes_) {
      detail::pack_record(record, results[i]);
      if (columns_.point) detail::pack_point(record, detail::point_or_nan(at, i));
    }
    output_.write(std::string_view(records_.data(), records_.size()));
    rows_ += results.size();
  }

  void commit() override {
    output_.rewrite(0, detail::npy_preamble(descr_, rows_));
    output_.commit();
  }

 private:
  OutputTarget output_;
  ResultColumns columns_;
  std::string_view descr_;
  std::size_t record_bytes_;
  std::vector<char> records_;
  std::uint64_t rows_ = 0;
};

// Records into the caller's memory (a numpy array the Python module hands over).
class MemoryResultWriter final : public ResultWriter {
 public:
  MemoryResultWriter(std::span<char> records, std::span<const char*> reasons, ResultColumns columns)
      : records_(records), reasons_(reasons), columns_(columns), record_bytes_(detail::record_bytes_for(columns)) {}

  ResultColumns columns() const override { return columns_; }
  void write(std::span<const PointResult> results) override { write_with_points(results, {}); }

  void write_with_points(std::span<const PointResult> results, std::span<const Point3> at) override {
    if (results.size() > (records_.size() - written_ * record_bytes_) / record_bytes_ ||
        (!reasons_.empty() && results.size() > reasons_.size() - written_))
      throw InputError("results: more rows than the " + std::to_string(records_.size() / record_bytes_) +
                       " the output holds");
    char* record = records_.data() + written_ * record_bytes_;
    for (std::size_t i = 0; i < results.size(); ++i, record += record_bytes_) {
      detail::pack_record(record, results[i]);
      if (columns_.point) detail::pack_point(record, detail::point_or_nan(at, i));
      if (!reasons_.empty()) reasons_[written_ + i] = results[i].reason;
    }
    written_ += results.size();
  }

  void commit() override {}

 private:
  std::span<char> records_;
  std::span<const char*> reasons_;
  ResultColumns columns_;
  std::size_t record_bytes_;
  std::size_t written_ = 0;
};

}  // namespace

std::string_view result_descr(ResultColumns columns) { return detail::result_descr_for(columns); }
std::size_t result_record_bytes(ResultColumns columns) { return detail::record_bytes_for(columns); }

std::unique_ptr<ResultWriter> open_results(std::span<char> records, std::span<const char*> reasons,
                                           ResultColumns columns) {
  return std::make_unique<MemoryResultWriter>(records, reasons, columns);
}

std::unique_ptr<ResultWriter> open_results(const std::string& path, int threads, ResultColumns columns) {
  if (detail::has_npy_extension(path)) return std::make_unique<NpyResultWriter>(path, columns);
  return std::make_unique<CsvResultWriter>(path, threads, columns);
}

void write_results_csv(const std::string& path, std::span<const PointResult> results) {
  CsvResultWriter writer(path, 0, {});
  writer.write(results);
  writer.commit();
}

}  // namespace bezinv
