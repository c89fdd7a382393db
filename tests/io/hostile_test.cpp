// Hostile input files (io.hpp): sizes that must not reach an allocation, text that must not reach
// a terminal raw, fields that must not be ignored. Every refusal is an InputError of one line that
// names the file and the field or line, holds no control byte, and stays short however long the
// offending text is. The limits themselves are checked at their boundaries.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <iterator>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/io.hpp"
#include "io/read_points_csv.hpp"
#include "quote.hpp"
#include "io/whole_file.hpp"
#include "support/scratch_directory.hpp"

namespace bezinv {
namespace {

using detail::escaped_excerpt;
using detail::kExcerptChars;
using detail::quoted_excerpt;
using test_support::ScratchDirectory;

// Longest message allowed besides the file's path: a few quoted excerpts and the fixed text.
constexpr std::size_t kMaxMessage = 500;

bool has_raw_control(std::string_view text) {
  return std::any_of(text.begin(), text.end(), [](char c) {
    const auto byte = static_cast<unsigned char>(c);
    return byte < 0x20 || byte == 0x7F;
  });
}

// `read` must throw an InputError of one line, free of control bytes, at most kMaxMessage longer
// than `path`, containing `path` and every fragment.
void expect_clean_error(const std::function<void()>& read, const std::string& path,
                        std::initializer_list<std::string> fragments) {
  try {
    read();
    ADD_FAILURE() << "no InputError; expected one mentioning " << *fragments.begin();
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_FALSE(has_raw_control(message)) << "raw control byte in: " << escaped_excerpt(message);
    EXPECT_LE(message.size(), path.size() + kMaxMessage) << escaped_excerpt(message);
    EXPECT_TRUE(message.starts_with(path)) << escaped_excerpt(message);
    for (const std::string& fragment : fragments)
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "'" << fragment << "' missing in: " << escaped_excerpt(message);
  }
}

// ---------------------------------------------------------------------------------------------
// quoted_excerpt: the one function every message quotes file content through

TEST(QuotedExcerpt, ShowsEveryControlCharacterAsAVisibleEscape) {
  for (int c = 0; c < 0x20; ++c) {
    const std::string text = std::string("a") + static_cast<char>(c) + "b";
    const std::string quoted = quoted_excerpt(text);
    EXPECT_FALSE(has_raw_control(quoted)) << c;
    EXPECT_TRUE(quoted.starts_with("\"a\\")) << quoted;
  }
  EXPECT_EQ(quoted_excerpt("\x1b[31mred\x1b[0m"), "\"\\x1b[31mred\\x1b[0m\"");
  EXPECT_EQ(quoted_excerpt("a\nb\rc\td"), "\"a\\nb\\rc\\td\"");
  EXPECT_EQ(quoted_excerpt(std::string("nul\0here", 8)), "\"nul\\x00here\"");
  EXPECT_EQ(quoted_excerpt("del\x7f"), "\"del\\x7f\"");
  // The delimiters and the escape character itself, so that an excerpt reads back unambiguously.
  EXPECT_EQ(quoted_excerpt("say \"hi\" \\ bye"), "\"say \\\"hi\\\" \\\\ bye\"");
  EXPECT_EQ(quoted_excerpt(""), "\"\"");
  EXPECT_EQ(escaped_excerpt("'<f4'"), "'<f4'");
}

TEST(QuotedExcerpt, KeepsReadableUnicodeButEscapesWhatATerminalWouldAct) {
  EXPECT_EQ(quoted_excerpt("Bézier 曲線 🙂"), "\"Bézier 曲線 🙂\"");
  // Not UTF-8: a lone 8-bit CSI (0x9b), 0xff, an overlong '/', a surrogate, a cut-off sequence.
  EXPECT_EQ(quoted_excerpt("\x9b" "31m"), "\"\\x9b31m\"");
  EXPECT_EQ(quoted_excerpt("\xff"), "\"\\xff\"");
  EXPECT_EQ(quoted_excerpt("\xc0\xaf"), "\"\\xc0\\xaf\"");
  EXPECT_EQ(quoted_excerpt("\xed\xa0\x80"), "\"\\xed\\xa0\\x80\"");
  EXPECT_EQ(quoted_excerpt("\xe6\x9b"), "\"\\xe6\\x9b\"");
  // UTF-8 of a C1 control, bidi overrides and isolates, zero-width and line separators.
  EXPECT_EQ(quoted_excerpt("\xc2\x9b" "2J"), "\"\\u009b2J\"");
  EXPECT_EQ(quoted_excerpt("abc\xe2\x80\xae" "fed"), "\"abc\\u202efed\"");
  EXPECT_EQ(quoted_excerpt("\xe2\x81\xa6x\xe2\x81\xa9"), "\"\\u2066x\\u2069\"");
  EXPECT_EQ(quoted_excerpt("a\xe2\x80\x8b" "b\xe2\x80\xa8" "c\xef\xbb\xbf"), "\"a\\u200bb\\u2028c\\ufeff\"");
}

TEST(QuotedExcerpt, CutsLongTextAndGivesItsSize) {
  const std::string megabyte(1 << 20, 'x');
  const std::string quoted = quoted_excerpt(megabyte);
  EXPECT_EQ(quoted, "\"" + std::string(kExcerptChars, 'x') + "\"...(1048576 bytes)");
  EXPECT_EQ(quoted_excerpt(std::string(kExcerptChars, 'y')), "\"" + std::string(kExcerptChars, 'y') + "\"");
  // Escapes count as what they print; a long run of them is cut too.
  const std::string escapes(10000, '\x1b');
  EXPECT_LE(quoted_excerpt(escapes).size(), kExcerptChars + 40);
  EXPECT_NE(quoted_excerpt(escapes).find("...(10000 bytes)"), std::string::npos);
  // Never in the middle of a UTF-8 sequence.
  std::string accents;
  for (int i = 0; i < 200; ++i) accents += "é";
  const std::string cut = escaped_excerpt(accents);
  const std::string kept = cut.substr(0, cut.find("..."));
  EXPECT_EQ(kept.size() % 2, 0u);
  EXPECT_EQ(kept, accents.substr(0, kept.size()));
  EXPECT_NE(cut.find("...(400 bytes)"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// .npy headers

// A .npy file: magic, version, the given header length field (not necessarily the truth), dict.
std::string npy_bytes(std::string_view dict, int major = 1, std::int64_t claimed_length = -1, std::string_view data = {}) {
  const std::size_t length_bytes = major == 1 ? 2 : 4;
  const std::uint64_t length = claimed_length >= 0 ? static_cast<std::uint64_t>(claimed_length) : dict.size();
  std::string bytes = "\x93NUMPY";
  bytes += static_cast<char>(major);
  bytes += '\0';
  for (std::size_t i = 0; i < length_bytes; ++i) bytes += static_cast<char>((length >> (8 * i)) & 0xff);
  return bytes + std::string(dict) + std::string(data);
}

// The dict np.save writes: padded with spaces so that the data starts at a multiple of 64, then '\n'.
std::string padded_dict(const std::string& dict, int major = 1) {
  const std::size_t preamble = major == 1 ? 10 : 12;
  std::string padded = dict;
  while ((preamble + padded.size() + 1) % 64 != 0) padded += ' ';
  return padded + '\n';
}

std::string points_dict(const std::string& shape = "(1, 2)") {
  return "{'descr': '<f8', 'fortran_order': False, 'shape': " + shape + ", }";
}

class NpyHostile : public ::testing::Test {
 protected:
  ScratchDirectory scratch{"bezinv-hostile-npy-test-"};
  std::vector<Curve> curves = [] {
    std::vector<Curve> list(1);
    list[0].id = "a";
    return list;
  }();
  const std::string one_point = std::string(16, '\0');

  void expect_refused(const std::string& bytes, std::initializer_list<std::string> fragments) {
    const std::string path = scratch.write("points.npy", bytes);
    expect_clean_error([&] { open_points(path, curves, {"a", ""}); }, path, fragments);
  }
};

TEST_F(NpyHostile, RefusesAHeaderLengthBeyondNumpysLimitBeforeAllocatingIt) {
  // 208 bytes claiming a 4 GiB header: refused from the length field alone.
  for (const int major : {2, 3})
    for (const std::int64_t claimed : {std::int64_t{0xFFFFFFFF}, std::int64_t{1} << 31, std::int64_t{10001}})
      expect_refused(npy_bytes(points_dict() + std::string(140, ' '), major, claimed),
                     {"header: length " + std::to_string(claimed) + " bytes", "10000"});
  expect_refused(npy_bytes(points_dict(), 1, 0xFFFF), {"header: length 65535 bytes", "10000"});
}

TEST_F(NpyHostile, ReadsAHeaderOfExactlyNumpysLimit) {
  std::string dict = points_dict();
  dict += std::string(10000 - dict.size() - 1, ' ') + '\n';
  ASSERT_EQ(dict.size(), 10000u);
  const std::string path = scratch.write("points.npy", npy_bytes(dict, 2, -1, one_point));
  EXPECT_EQ(open_points(path, curves, {"a", ""})->progress().points_total, 1u);
}

TEST_F(NpyHostile, RefusesTextAfterTheDict) {
  for (const std::string& junk : std::initializer_list<std::string>{"junk", "\x1b[2J\x1b[H", std::string("\0\0", 2), "\t", "{}", "#", "\r"}) {
    const std::string dict = padded_dict(points_dict() + junk);
    expect_refused(npy_bytes(dict, 1, -1, one_point), {"header: text after the dict"});
  }
  // The padding numpy writes, and none at all, are fine.
  for (const std::string& dict : {padded_dict(points_dict()), points_dict(), points_dict() + "\n"}) {
    const std::string path = scratch.write("fine.npy", npy_bytes(dict, 1, -1, one_point));
    EXPECT_EQ(open_points(path, curves, {"a", ""})->progress().points_total, 1u);
  }
}

TEST_F(NpyHostile, EscapesHeaderTextQuotedInMessages) {
  expect_refused(npy_bytes(padded_dict("{'descr': '<f8', '\x1b]0;owned\x07': 1, 'fortran_order': False, 'shape': (1, 2)}"), 1,
                           -1, one_point),
                 {"header: unexpected key \"\\x1b]0;owned\\x07\""});
  expect_refused(npy_bytes(padded_dict("{'descr': '<f8\x1b[31m', 'fortran_order': False, 'shape': (1, 2)}"), 1, -1,
                           one_point),
                 {"header: dtype '<f8\\x1b[31m' is not '<f8'"});
  // A structured dtype is shown as written, cut short.
  std::string fields = "[";
  for (int i = 0; i < 200; ++i) fields += "('f" + std::to_string(i) + "', '<f8'), ";
  fields += "]";
  expect_refused(npy_bytes(padded_dict("{'descr': " + fields + ", 'fortran_order': False, 'shape': (1, 2)}"), 1, -1,
                           one_point),
                 {"header: dtype [('f0', '<f8')", "bytes) is not '<f8'"});
}

TEST_F(NpyHostile, RefusesShapesWhoseSizeOverflowsWithTheTrueByteCount) {
  // rows x 16 bytes wraps around 2^64 to 0 or a small number; the message gives the exact product.
  const std::pair<const char*, const char*> cases[] = {
      {"1152921504606846976", "18446744073709551616"},   // 2^60 rows: 2^64 bytes, wraps to 0
      {"1152921504606846977", "18446744073709551632"},   // wraps to 16: one row's worth
      {"18446744073709551615", "295147905179352825840"}, // the largest shape numpy could write
      {"1152921504606846975", "18446744073709551600"},   // fits 64 bits, still not this file
  };
  for (const auto& [rows, bytes] : cases)
    expect_refused(npy_bytes(padded_dict(points_dict(std::string("(") + rows + ", 2)")), 1, -1, one_point),
                   {"data:", std::string("shape (") + rows + ", 2) needs " + bytes + " bytes", "the file has 16"});
}

TEST_F(NpyHostile, RefusesAnOverflowingShapeFromAPipe) {
  // Nothing to measure: the shape alone is refused.
  const std::string fifo = scratch.path("points.npy");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const auto old_handler = std::signal(SIGPIPE, SIG_IGN);
  std::thread writer([&] {
    std::ofstream out(fifo, std::ios::binary);
    out << npy_bytes(padded_dict(points_dict("(1152921504606846976, 2)")), 1, -1, one_point);
  });
  expect_clean_error([&] { open_points(fifo, curves, {"a", ""}); }, fifo,
                     {"shape (1152921504606846976, 2) needs 18446744073709551616 bytes", "more than any file holds"});
  writer.join();
  std::signal(SIGPIPE, old_handler);
}

// ---------------------------------------------------------------------------------------------
// POINTS.csv

class CsvHostile : public ::testing::Test {
 protected:
  ScratchDirectory scratch{"bezinv-hostile-csv-test-"};
  std::vector<Curve> curves = [] {
    std::vector<Curve> list(2);
    list[0].id = "a";
    list[1].id = "b";
    return list;
  }();

  std::vector<PointRow> read(std::string_view csv) { return detail::read_points_csv(scratch.write("points.csv", csv), curves); }
  void expect_refused(std::string_view csv, std::initializer_list<std::string> fragments) {
    const std::string path = scratch.write("points.csv", csv);
    expect_clean_error([&] { detail::read_points_csv(path, curves); }, path, fragments);
  }
};

TEST_F(CsvHostile, RefusesALineLongerThanTheLimitNamingIt) {
  constexpr std::size_t kLimit = std::size_t{1} << 20;
  // A row padded with blanks to exactly the limit is read; one byte more is refused, wherever the
  // line is and whether or not a newline ends it.
  const std::string at_limit = "a,1,2" + std::string(kLimit - 5, ' ');
  EXPECT_EQ(read("curve,x,y\nb,0,0\n" + at_limit + "\n").size(), 2u);
  EXPECT_EQ(read("curve,x,y\nb,0,0\r\n" + at_limit + "\r\n").size(), 2u);
  expect_refused("curve,x,y\nb,0,0\n" + at_limit + " \nb,0,0\n", {":3:", "line longer than 1048576 bytes"});
  expect_refused("curve,x,y\nb,0,0\n" + at_limit + " ", {":3:", "line longer than 1048576 bytes"});
  expect_refused(std::string(3 * kLimit, 'x'), {":1:", "line longer than 1048576 bytes"});
  expect_refused("curve,x,y\n" + std::string(5 * kLimit, '\0'), {":2:", "line longer than"});
  // Blank lines too are lines.
  expect_refused("\n\n" + std::string(kLimit + 1, ' '), {":3:", "line longer than"});
}

// Found by tests/fuzz/fuzz_points_csv, which ran out of file descriptors after about a thousand
// inputs: a CSV refused for its header left its file open (the reader's constructor threw, so its
// destructor never ran). Every refused file is closed, and so is every read one.
TEST_F(CsvHostile, RefusedAndReadFilesLeaveNoDescriptorOpen) {
  auto open_descriptors = [] {
    return std::distance(std::filesystem::directory_iterator("/proc/self/fd"), std::filesystem::directory_iterator{});
  };
  const std::string bad = scratch.write("bad.csv", "x,y\n1,2\n"), empty = scratch.write("empty.csv", ""),
                    good = scratch.write("good.csv", "curve,x,y\na,1,2\n");
  const auto before = open_descriptors();
  for (int i = 0; i < 50; ++i) {
    EXPECT_THROW(open_points(bad, curves), InputError);
    EXPECT_THROW(open_points(empty, curves), InputError);
    EXPECT_EQ(detail::read_points_csv(good, curves).size(), 1u);
  }
  EXPECT_EQ(open_descriptors(), before);
}

TEST_F(CsvHostile, StopsReadingDevZeroAtTheFirstLine) {
  expect_clean_error([&] { detail::read_points_csv("/dev/zero", curves); }, "/dev/zero", {"/dev/zero:1:", "line longer than"});
}

TEST_F(CsvHostile, EscapesAndCutsTheLinesItQuotes) {
  for (const std::string control : {"\x1b[31m", "\x1b]0;title\x07", "\r", "\x08\x08\x08", "\x7f", "\xc2\x9b" "2J"}) {
    expect_refused("curve,x,y\na,1,2," + control + "\n", {":2:", "expected 3 fields (curve,x,y), found 4"});
    expect_refused("curve," + control + ",y\na,1,2\n", {":1:", "header must be 'curve,x,y'"});
  }
  // A 500 kB row (under the line limit) is named, not repeated.
  expect_refused("curve,x,y\na,1,2," + std::string(500000, 'z') + "\n", {":2:", "found 4", "bytes)"});
}

TEST_F(CsvHostile, RefusesAQuoteThatDoesNotCloseOnItsLine) {
  expect_refused("curve,x,y\n\"a,1,2\n", {":2:", "field 1:", "does not close on its line"});
  expect_refused("curve,x,y\na,\"1\n2\",3\n", {":2:", "field 2:", "does not close on its line"});
  expect_refused("curve,x,y\na,1,\"2\"\"\n", {":2:", "field 3:", "does not close"});
  expect_refused("\"curve,x,y\n", {":1:", "field 1:", "does not close"});
  expect_refused("curve,x,y\n\"a\"b,1,2\n", {":2:", "field 1: text after the closing quote: \"b\""});
  expect_refused("curve,x,y\na,\"1\" 2,3\n", {":2:", "field 2: text after the closing quote: \"2\""});
}

// ---------------------------------------------------------------------------------------------
// CURVES.json

class CurvesHostile : public ::testing::Test {
 protected:
  ScratchDirectory scratch{"bezinv-hostile-curves-test-"};

  void expect_refused(std::string_view json, std::initializer_list<std::string> fragments) {
    const std::string path = scratch.write("curves.json", json);
    expect_clean_error([&] { read_curves_json(path); }, path, fragments);
  }
};

TEST_F(CurvesHostile, RefusesUnknownFieldsNamingTheCurveAndTheField) {
  const std::string bezier = R"("id": "c1", "kind": "bezier", "points": [[0, 0], [1, 1]])";
  const std::string rational_bezier = R"("id": "c1", "kind": "rational_bezier", "points": [[0, 0], [1, 1]], "weights": [1, 1])";
  const std::string rational =
      R"("id": "c1", "kind": "rational", "x_num": [0, 1], "x_den": [1, 1], "y_num": [0, 1], "y_den": [1, 1])";
  const std::string first = R"({"id": "c0", "kind": "bezier", "points": [[0, 0], [1, 0]]}, )";
  for (const std::string& curve : {bezier, rational_bezier, rational})
    for (const std::string key : {"weight", "Weights", "weights ", "point", "x-num", "", "id2", "\\u001b[31m", "comment"}) {
      const std::string json = "{\"curves\": [" + first + "{" + curve + ", \"" + key + "\": [1, 1]}]}";
      const std::string shown = key == "\\u001b[31m" ? std::string("\\x1b[31m") : key;
      expect_refused(json, {"curves[1] (id \"c1\"): \"" + shown + "\": unknown field (kind \""});
    }
  // A field of another kind is named as such.
  expect_refused("{\"curves\": [{" + bezier + ", \"weights\": [1, 1]}]}", {"curves[0] (id \"c1\"): weights: not a field of kind \"bezier\""});
  expect_refused("{\"curves\": [{" + rational + ", \"points\": [[0, 0], [1, 1]]}]}", {"curves[0] (id \"c1\"): points: not a field of kind \"rational\""});
  expect_refused("{\"curves\": [{" + rational_bezier + ", \"y_den\": [1, 1]}]}", {"y_den: not a field of kind \"rational_bezier\""});
}

TEST_F(CurvesHostile, RefusesUnknownTopLevelFields) {
  const std::string list = R"("curves": [{"id": "a", "kind": "bezier", "points": [[0, 0], [1, 1]]}])";
  for (const std::string key : {"curve", "version", "Curves", "$schema", "\\u009b"}) {
    const std::string shown = key == "\\u009b" ? std::string("\\u009b") : key;
    expect_refused("{" + list + ", \"" + key + "\": 1}", {"\"" + shown + "\": unknown field (the top level has only \"curves\")"});
  }
}

TEST_F(CurvesHostile, EscapesAndCutsIdsKindsAndKeysInMessages) {
  // Control characters in ids are refused, and the message shows them escaped.
  for (const std::string id : {"\\u001b[31mred", "a\\u0000b", "tab\\tinside", "bell\\u0007", "del\\u007f"})
    expect_refused("{\"curves\": [{\"id\": \"" + id + "\", \"kind\": \"bezier\", \"points\": [[0, 0], [1, 1]]}]}",
                   {"curves[0] (id \"", "id: must not contain", "control characters"});
  // Other ids reach validate(), whose message quotes them the same way.
  expect_refused(R"({"curves": [{"id": "rtl\u202eevil", "kind": "bezier", "points": [[0, 0]]}]})",
                 {"curves[0] (id \"rtl\\u202eevil\"): degree must be at least 1"});
  // A megabyte id or kind is cut short with its size.
  const std::string long_id(1000000, 'i');
  expect_refused(R"({"curves": [{"id": ")" + long_id + R"(", "kind": "spline"}]})",
                 {"curves[0] (id \"iiii", "...(1000000 bytes)", "kind: unknown \"spline\""});
  expect_refused(R"({"curves": [{"id": "a", "kind": ")" + std::string(300000, 'k') + "\\u001b\"}]}",
                 {"kind: unknown \"kkk", "...(300001 bytes)"});
  expect_refused(R"({"curves": [{"id": "a", "kind": "\u001b[2Jbezier"}]})", {"kind: unknown \"\\x1b[2Jbezier\""});
  // Keys in a path or a duplicate-key message.
  expect_refused(R"({"curves": [{"id": "a", "\u001b": 1, "\u001b": 2}]})", {"duplicate key \"\\x1b\""});
  expect_refused("{\"curves\": [{\"" + std::string(200000, 'q') + "\": [1e999]}]}",
                 {"curves[0].\"qqq", "...(200000 bytes)", "not a finite double"});
}

TEST_F(CurvesHostile, BoundsTheParserMessagesThatQuoteTheFile) {
  // nlohmann quotes the token it stopped at, a whole unterminated string or number if need be.
  expect_refused("{\"curves\": [{\"id\": \"" + std::string(2000000, 's'), {"malformed JSON", "bytes)"});
  expect_refused("{\"curves\": [{\"id\": \"\x1b[31m\"}]}", {"malformed JSON", "control character"});
  expect_refused("{\"curves\": [1" + std::string(500000, '0') + "]}", {"not a finite double", "bytes)"});
  expect_refused("{\"curves\": [\xff\xfe]}", {"malformed JSON"});
}

TEST_F(CurvesHostile, RefusesDeepNesting) {
  expect_refused(std::string(1000000, '['), {"nested deeper than 16 arrays and objects"});
  expect_refused(R"({"curves": [{"id": "a", "kind": "bezier", "points": )" + std::string(100, '[') + std::string(100, ']') + "}]}",
                 {"curves[0].points", "nested deeper than 16"});
  // The format's own depth (5) is well within the limit.
  const std::string path = scratch.write("ok.json", R"({"curves": [{"id": "a", "kind": "bezier", "points": [[0, 0], [1, 1]]}]})");
  EXPECT_EQ(read_curves_json(path).size(), 1u);
}

TEST_F(CurvesHostile, RefusesAFileLargerThanTheCapBeforeReadingIt) {
  // Sparse: 300 MiB of size, no disk and nothing read.
  const std::string path = scratch.path("huge.json");
  std::filesystem::resize_file(scratch.write("huge.json", "{"), std::uint64_t{300} << 20);
  expect_clean_error([&] { read_curves_json(path); }, path,
                     {std::to_string(std::uint64_t{300} << 20) + " bytes, more than 268435456 bytes, the limit for CURVES.json"});
}

TEST_F(CurvesHostile, StopsADeviceOrAPipeAtTheCap) {
  // The cap of read_whole_file is the caller's; a small one shows where the reading stops.
  expect_clean_error([&] { detail::read_whole_file("/dev/zero", 100000, "TEST"); }, "/dev/zero",
                     {"more than 100000 bytes, the limit for TEST"});
  const std::string fifo = scratch.path("curves.json");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const auto old_handler = std::signal(SIGPIPE, SIG_IGN);
  std::thread writer([&] {
    std::ofstream out(fifo, std::ios::binary);
    out << std::string(1 << 20, ' ');  // more than the cap, less than forever
  });
  expect_clean_error([&] { detail::read_whole_file(fifo, 100000, "TEST"); }, fifo, {"more than 100000 bytes"});
  writer.join();
  std::signal(SIGPIPE, old_handler);
  // At the cap exactly, it reads.
  EXPECT_EQ(detail::read_whole_file(scratch.write("exact.json", std::string(100000, ' ')), 100000, "TEST").size(), 100000u);
  // /dev/zero through the real reader stops at the real cap.
  expect_clean_error([&] { read_curves_json("/dev/zero"); }, "/dev/zero", {"more than 268435456 bytes"});
}

}  // namespace
}  // namespace bezinv
