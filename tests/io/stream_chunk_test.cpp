// invert_stream's chunks: as many points as chunk_points (the last one fewer), whatever the
// reader hands over per call, and buffers no larger than the input needs. A scripted reader and a
// recording writer stand in for the files; every row is a rejected one (curve -1), so no plan is
// involved and each result can be traced back to its row by its reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "bezinv/io.hpp"
#include "support/sanitizers.hpp"

namespace bezinv {
namespace {

// `total` rows; reason i names row i. Says how many there are only if `known_total` (as the .npy
// reader does; the CSV reader cannot).
class ScriptedReader final : public PointReader {
 public:
  ScriptedReader(std::size_t total, bool known_total) : total_(total), known_total_(known_total) {
    for (std::size_t i = 0; i < total; ++i) reasons_.push_back(std::to_string(i));
  }

  std::size_t read(std::span<PointRow> rows) override {
    largest_request_ = std::max(largest_request_, rows.size());
    const std::size_t count = std::min(rows.size(), total_ - next_);
    for (std::size_t i = 0; i < count; ++i) rows[i] = PointRow{-1, {0.0, 0.0}, reasons_[next_ + i].c_str()};
    next_ += count;
    return count;
  }

  ReadProgress progress() const override {
    ReadProgress progress;
    progress.points = next_;
    if (known_total_) progress.points_total = total_;
    return progress;
  }

  std::size_t largest_request() const { return largest_request_; }

 private:
  std::size_t total_, next_ = 0;
  bool known_total_;
  std::vector<std::string> reasons_;
  std::size_t largest_request_ = 0;
};

class RecordingWriter final : public ResultWriter {
 public:
  void write(std::span<const PointResult> results) override {
    chunks.push_back(results.size());
    for (const PointResult& result : results) reasons.emplace_back(result.reason);
  }
  void commit() override {}

  std::vector<std::size_t> chunks;
  std::vector<std::string> reasons;
};

std::vector<std::size_t> expected_chunks(std::size_t total, std::size_t chunk) {
  std::vector<std::size_t> sizes;
  for (std::size_t done = 0; done < total; done += chunk) sizes.push_back(std::min(chunk, total - done));
  return sizes;
}

TEST(IoStreamChunks, EveryChunkIsFullButTheLastAndRowsStayInOrder) {
  constexpr std::array<std::size_t, 7> kChunks = {1, 3, 65535, 65536, 65537, 150000, std::size_t{1} << 24};
  for (const bool known_total : {false, true}) {
    for (const std::size_t total : {std::size_t{0}, std::size_t{1}, std::size_t{65536}, std::size_t{200001}}) {
      for (std::size_t c = 0; c < kChunks.size(); ++c) {
        const std::size_t chunk = kChunks[c];
        if (chunk < 8 && total > 70000) continue;  // a chunk of one row each: slow, nothing new
        // Under the sanitizers the large inputs take each chunk size with one of the two readers,
        // in turn (support/sanitizers.hpp).
        if (test_support::kSanitizerTree && total > 70000 && (c + known_total) % 2 != 0) continue;
        ScriptedReader reader(total, known_total);
        RecordingWriter writer;
        const StreamSummary summary = invert_stream(reader, writer, std::span<const InversionPlan>{}, {}, chunk);
        EXPECT_EQ(summary.points, total);
        EXPECT_EQ(summary.by_status[static_cast<std::size_t>(Status::invalid_input)], total);
        EXPECT_EQ(writer.chunks, expected_chunks(total, chunk))
            << "total " << total << ", chunk " << chunk << ", known total " << known_total;
        ASSERT_EQ(writer.reasons.size(), total);
        for (std::size_t i = 0; i < total; ++i) ASSERT_EQ(writer.reasons[i], std::to_string(i)) << i;
      }
    }
  }
}

// A reader that knows its total is never asked for more rows than it has left; one that does not
// is asked for at most twice what it turned out to have (the buffer doubles as it fills), and
// never for a whole large chunk up front.
TEST(IoStreamChunks, BuffersGrowWithTheInputNotWithChunkPoints) {
  constexpr std::size_t kHuge = std::size_t{1} << 24;
  for (const std::size_t total : {std::size_t{5}, std::size_t{100000}, std::size_t{300000}}) {
    ScriptedReader counted(total, true);
    RecordingWriter writer;
    invert_stream(counted, writer, std::span<const InversionPlan>{}, {}, kHuge);
    EXPECT_LE(counted.largest_request(), total);

    ScriptedReader uncounted(total, false);
    RecordingWriter other;
    invert_stream(uncounted, other, std::span<const InversionPlan>{}, {}, kHuge);
    EXPECT_LE(uncounted.largest_request(), std::max<std::size_t>(2 * total, std::size_t{1} << 16)) << total;
    EXPECT_EQ(other.chunks, std::vector<std::size_t>{total});
  }
}

}  // namespace
}  // namespace bezinv
