// End to end: the real `bezinv` on hostile input files. Each run is bounded, in address space
// (unless AddressSanitizer, which reserves terabytes of it, is in the build) and in time, so a
// regression to allocating what a file claims fails the test instead of taking the machine's
// memory. A refusal must be exit 2, one stderr line naming the file and the field or line, free
// of control bytes and short however long the offending text is, and no OUT file.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "support/run_bezinv.hpp"
#include "support/sanitizers.hpp"
#include "support/scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;

using bezinv::test_support::quoted;
using bezinv::test_support::read_file;
using bezinv::test_support::ScratchDirectory;

// Room for a normal run and for reading CURVES.json up to its cap, far below what the hostile
// files claim (4 GiB headers, 2^64-byte shapes, endless lines).
constexpr const char* kAddressSpace = "2147483648";
// Longest stderr line accepted: "bezinv: ", a scratch path, and a few 80-character excerpts.
constexpr std::size_t kMaxErrorLine = 600;

constexpr const char* kArchJson =
    R"({"curves": [{"id": "arch", "kind": "bezier", "points": [[0, 0], [1, 2], [3, 2], [4, 0]]}]})";

struct Refusal {
  int exit_code = -1;
  std::string err;
};

class CliHostileInput : public ::testing::Test {
 protected:
  ScratchDirectory scratch{"bezinv-cli-hostile-test-"};
  std::string curves = scratch.write("curves.json", kArchJson);
  std::string points = scratch.write("points.csv", "curve,x,y\narch,2,1.5\n");
  std::string out = scratch.path("out.csv");

  // `setup` runs first in the same shell (a background writer into a FIFO).
  Refusal run(const std::string& arguments, const std::string& setup = "") const {
    const std::string err = scratch.path("stderr.txt");
    std::string command = setup + "timeout 120 ";
    if (!bezinv::test_support::kSanitizerTree) command += std::string("prlimit --as=") + kAddressSpace + " ";
    command += std::string("'") + BEZINV_CLI_PATH + "' " + arguments + " >/dev/null 2>'" + err + "'";
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_file(err)};
  }

  std::string invert(const std::string& curves_path, const std::string& points_path, const std::string& extra = "") const {
    return "invert --curves " + quoted(curves_path) + " --points " + quoted(points_path) + " --out " + quoted(out) +
           extra;
  }

  void expect_refused(const std::string& arguments, std::initializer_list<std::string> fragments,
                      const std::string& setup = "") const {
    const Refusal result = run(arguments, setup);
    const std::string& err = result.err;
    EXPECT_EQ(result.exit_code, 2) << err;  // the input-error code: not a crash, not 124 (timeout)
    EXPECT_TRUE(err.starts_with("bezinv: ")) << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_TRUE(std::none_of(err.begin(), err.end() - (err.empty() ? 0 : 1), [](char c) {
      return static_cast<unsigned char>(c) < 0x20 || c == 0x7F;
    })) << "raw control byte on stderr";
    EXPECT_LE(err.size(), kMaxErrorLine) << err.substr(0, 2 * kMaxErrorLine);
    for (const std::string& fragment : fragments)
      EXPECT_NE(err.find(fragment), std::string::npos) << "'" << fragment << "' missing in: " << err;
    EXPECT_FALSE(fs::exists(out));
  }

  // A FIFO; afterwards any writer still waiting for a reader is let go (it meets a closed pipe).
  std::string fifo(const std::string& name) {
    const std::string path = scratch.path(name);
    EXPECT_EQ(mkfifo(path.c_str(), 0600), 0);
    fifos_.push_back(path);
    return path;
  }
  void TearDown() override {
    for (const std::string& path : fifos_) {
      const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK);
      if (fd >= 0) ::close(fd);
    }
  }

 private:
  std::vector<std::string> fifos_;
};

// .npy bytes with a header length field that need not be the dict's.
std::string npy(std::string_view dict, int major, std::uint64_t length, std::string_view data) {
  std::string bytes = "\x93NUMPY";
  bytes += static_cast<char>(major);
  bytes += '\0';
  for (int i = 0; i < (major == 1 ? 2 : 4); ++i) bytes += static_cast<char>((length >> (8 * i)) & 0xff);
  return bytes + std::string(dict) + std::string(data);
}
std::string npy(std::string_view dict, std::string_view data = std::string(16, '\0')) {
  return npy(dict, 1, dict.size(), data);
}

TEST_F(CliHostileInput, NpyHeadersThatClaimTooMuch) {
  const std::string dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (1, 2), }";
  // 208 bytes whose header length says 4 GiB (a reader that trusted it would allocate that first).
  for (const int major : {2, 3}) {
    const std::string bytes = npy(dict + std::string(208 - 12 - dict.size(), ' '), major, 0xFFFFFFFF, "");
    ASSERT_EQ(bytes.size(), 208u);
    const std::string path = scratch.write("claims.npy", bytes);
    expect_refused(invert(curves, path, " --curve arch"), {"claims.npy: header: length 4294967295 bytes", "10000"});
  }
  const std::string huge_shape = scratch.write(
      "shape.npy", npy("{'descr': '<f8', 'fortran_order': False, 'shape': (1152921504606846976, 2), }\n"));
  expect_refused(invert(curves, huge_shape, " --curve arch"),
                 {"shape.npy: data:", "shape (1152921504606846976, 2) needs 18446744073709551616 bytes", "the file has 16"});
}

TEST_F(CliHostileInput, NpyHeaderTextIsRefusedAndShownEscaped) {
  for (const std::string junk : {"\x1b[2J", "junk", "\x9b" "31m"}) {
    const std::string path =
        scratch.write("junk.npy", npy("{'descr': '<f8', 'fortran_order': False, 'shape': (1, 2), }" + junk + "\n"));
    expect_refused(invert(curves, path, " --curve arch"), {"junk.npy: header: text after the dict"});
  }
  const std::string key = scratch.write(
      "key.npy", npy("{'descr': '<f8', '\x1b]0;title\x07': 0, 'fortran_order': False, 'shape': (1, 2), }\n"));
  expect_refused(invert(curves, key, " --curve arch"), {"key.npy: header: unexpected key \"\\x1b]0;title\\x07\""});
}

TEST_F(CliHostileInput, InputsWithoutLineBreaksStopAtTheLimits) {
  // Devices: no size to check up front.
  expect_refused(invert(curves, "/dev/zero"), {"/dev/zero:1:", "line longer than 1048576 bytes"});
  expect_refused(invert("/dev/zero", points), {"/dev/zero: more than 268435456 bytes, the limit for CURVES.json"});
  // Endless pipes: blank lines for CURVES (valid JSON whitespace), one endless line for POINTS.
  const std::string curves_fifo = fifo("curves-fifo.json");
  expect_refused(invert(curves_fifo, points), {"curves-fifo.json: more than 268435456 bytes"},
                 "timeout 120 yes '' >" + quoted(curves_fifo) + " 2>/dev/null & ");
  const std::string points_fifo = fifo("points-fifo.csv");
  expect_refused(invert(curves, points_fifo), {"points-fifo.csv:1: line longer than"},
                 "(timeout 120 yes x | tr -d '\\n' >" + quoted(points_fifo) + ") 2>/dev/null & ");
  // A long line after good rows names its line.
  const std::string long_line =
      scratch.write("long.csv", "curve,x,y\narch,2,1.5\n" + std::string(2 << 20, '7') + ",1,2\narch,4,0\n");
  expect_refused(invert(curves, long_line), {"long.csv:3: line longer than 1048576 bytes"});
}

TEST_F(CliHostileInput, CurvesFileLargerThanTheCapIsRefusedFromItsSize) {
  const std::string path = scratch.write("big.json", kArchJson);
  fs::resize_file(path, std::uint64_t{1} << 30);  // sparse: nothing to read, nothing on disk
  expect_refused(invert(path, points), {"big.json: 1073741824 bytes, more than 268435456 bytes"});
}

TEST_F(CliHostileInput, UnknownCurveFieldsAreNamed) {
  for (const std::string field : {"weight", "wieghts", "Points", "x_nums"}) {
    const std::string path = scratch.write(
        "typo.json", R"({"curves": [{"id": "arch", "kind": "rational_bezier", "points": [[0, 0], [1, 2], [4, 0]], ")" +
                         field + R"(": [1, 2, 1]}]})");
    expect_refused(invert(path, points), {"typo.json: curves[0] (id \"arch\"): \"" + field + "\": unknown field"});
  }
  const std::string top = scratch.write("top.json", R"({"curves": [{"id": "arch", "kind": "bezier", "points": [[0, 0], [1, 1]]}], "units": "mm"})");
  expect_refused(invert(top, points), {"top.json: \"units\": unknown field"});
}

TEST_F(CliHostileInput, FileTextInMessagesIsEscapedAndCut) {
  // Control characters in an id, a kind, a CSV row; a megabyte id.
  const std::string id = scratch.write(
      "id.json", R"({"curves": [{"id": "\u001b[31mred\u001b[0m", "kind": "bezier", "points": [[0, 0], [1, 1]]}]})");
  expect_refused(invert(id, points), {"id.json: curves[0] (id \"\\x1b[31mred\\x1b[0m\"): id: must not contain"});
  const std::string kind = scratch.write(
      "kind.json", R"({"curves": [{"id": "a", "kind": "bezier\u0007\u0008\u0008", "points": [[0, 0], [1, 1]]}]})");
  expect_refused(invert(kind, points), {"kind.json: curves[0] (id \"a\"): kind: unknown \"bezier\\x07\\x08\\x08\""});
  const std::string row = scratch.write("row.csv", "curve,x,y\narch,2,1.5,\x1b]0;pwned\x07\n");
  expect_refused(invert(curves, row), {"row.csv:2: expected 3 fields", "\\x1b]0;pwned\\x07"});
  const std::string long_id = scratch.write(
      "long-id.json", R"({"curves": [{"id": ")" + std::string(1 << 20, 'i') + R"(", "kind": "bezier", "points": [[0, 0]]}]})");
  expect_refused(invert(long_id, points), {"long-id.json: curves[0] (id \"iiii", "...(1048576 bytes)", "degree"});
}

TEST_F(CliHostileInput, QuotedCsvFieldsGiveTheSameRowsAsBareOnes) {
  const std::string bare = scratch.write("bare.csv", "curve,x,y\narch,2,1.5\narch,4,0\n0,2,5\nnope,1,1\n");
  const std::string quoted_csv =
      scratch.write("quoted.csv", "\"curve\",\"x\",\"y\"\n\"arch\",\"2\",\"1.5\"\n\"arch\", 4 ,\"0\"\r\n\"0\",\"2\",\"5\"\n\"no\"\"pe\",1,1\n");
  ASSERT_EQ(run(invert(curves, bare)).exit_code, 0);
  const std::string expected = read_file(out);
  fs::remove(out);
  const Refusal result = run(invert(curves, quoted_csv));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(read_file(out), expected);
  EXPECT_EQ(std::count(expected.begin(), expected.end(), '\n'), 5);  // header + one row per point
  fs::remove(out);
  // A quoted field may not span lines.
  const std::string broken = scratch.write("broken.csv", "curve,x,y\narch,2,1.5\n\"ar\nch\",1,1\n");
  expect_refused(invert(curves, broken), {"broken.csv:3: field 1:", "does not close on its line"});
}

}  // namespace
