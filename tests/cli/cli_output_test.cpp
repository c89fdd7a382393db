// End to end: where `--out` goes, with the real `bezinv` binary. Each kind of target (absent,
// regular, hard-linked, symbolic link, dangling link, character device, FIFO, an input under
// another name) is checked by its effect on the file system afterwards, and an interrupted run
// by what it leaves behind. The results themselves are checked elsewhere (cli_test, cli_npy_test):
// here a run to a plain new file is the reference the other targets must receive.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <ios>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "support/npy_bytes.hpp"
#include "support/run_bezinv.hpp"
#include "support/sanitizers.hpp"
#include "support/scratch_directory.hpp"
#include "support/split.hpp"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

using bezinv::test_support::Outcome;
using bezinv::test_support::read_file;
using bezinv::test_support::run_bezinv;
using bezinv::test_support::ScratchDirectory;
using bezinv::test_support::split;

constexpr const char* kCubicJson = R"({"curves": [
  {"id": "cubic", "kind": "bezier", "points": [[0, 0], [1, 2], [3, 2], [4, 0]]}
]})";
// Points of the cubic at t = 0, 0.5, 1 and one off it.
constexpr const char* kPointsCsv = "curve,x,y\ncubic,0,0\ncubic,2,1.5\ncubic,4,0\ncubic,2,5\n";

// No bounded wait below is meant to be reached: it only stops a broken build from hanging ctest.
constexpr auto kPatience = 60s;

using bezinv::test_support::append_le;
using bezinv::test_support::npy_file;

// A file of `rows` points, (x, y) each.
std::string points_npy(std::size_t rows, const std::string& data) {
  return npy_file("<f8", "(" + std::to_string(rows) + ", 2)", data);
}

// Points on the cubic x = 3t + 3t^2 - 2t^3, y = 6t(1 - t), cycling through 1000 parameters.
std::string cubic_points_npy(std::size_t rows) {
  std::string data;
  data.reserve(rows * 16);
  for (std::size_t i = 0; i < rows; ++i) {
    const double t = static_cast<double>(i % 1000) / 999.0;
    append_le(data, 3 * t + 3 * t * t - 2 * t * t * t);
    append_le(data, 6 * t * (1 - t));
  }
  return points_npy(rows, data);
}

// The same, written to `path` 1000 rows at a time: a big input without a big string in this
// process (whose memory would otherwise stay its peak for the rest of the tests).
std::string write_cubic_points_npy(const std::string& path, std::size_t rows) {
  const std::string block = cubic_points_npy(1000);
  const std::size_t data_offset = block.size() - 1000 * 16;
  std::ofstream out(path, std::ios::binary);
  const std::string header = points_npy(rows, "");
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  for (std::size_t done = 0; done < rows; done += 1000) {
    const std::size_t count = std::min<std::size_t>(1000, rows - done);
    out.write(block.data() + data_offset, static_cast<std::streamsize>(count * 16));
  }
  return path;
}

// kPointsCsv's points.
std::string four_points_npy() {
  std::string data;
  for (const double coordinate : {0.0, 0.0, 2.0, 1.5, 4.0, 0.0, 2.0, 5.0}) append_le(data, coordinate);
  return points_npy(4, data);
}

std::string cubic_points_csv(std::size_t rows) {
  std::string text = "curve,x,y\n";
  char row[64];
  for (std::size_t i = 0; i < rows; ++i) {
    const double t = static_cast<double>(i % 1000) / 999.0;
    std::snprintf(row, sizeof row, "cubic,%.17g,%.17g\n", 3 * t + 3 * t * t - 2 * t * t * t, 6 * t * (1 - t));
    text += row;
  }
  return text;
}

// Not `quoted`: with a std::string argument, argument-dependent lookup also finds std::quoted.
std::string shell_quoted(const std::string& text) { return bezinv::test_support::quoted(text); }

struct stat lstat_of(const std::string& path) {
  struct stat status {};
  EXPECT_EQ(::lstat(path.c_str(), &status), 0) << path << ": " << std::strerror(errno);
  return status;
}

// Names in `directory` that look like a temporary output (OUT.tmp.<pid>.<n>).
std::vector<std::string> temporaries_in(const fs::path& directory) {
  std::vector<std::string> found;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(directory, error))
    if (entry.path().filename().string().find(".tmp.") != std::string::npos) found.push_back(entry.path().string());
  return found;
}

std::vector<std::string> entries_of(const fs::path& directory) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(directory)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// ---- Running the binary without a shell: signals, peak memory, bounded waits -----------------

struct Ended {
  bool in_time = false;
  int status = 0;
  struct rusage usage {};
};

// bezinv with `arguments`, stdout and stderr to files. The terminating signals are reset to their
// default in the child, whatever this process inherited (a shell runs background jobs with
// SIGINT ignored, and bezinv keeps an ignored signal ignored). fork, not posix_spawn (vfork): a
// child that shared this process's memory until exec reports this process's peak as its own
// ru_maxrss, and one test measures bezinv's.
pid_t spawn_bezinv(const std::vector<std::string>& arguments, const std::string& out_file, const std::string& err_file) {
  // Everything the child needs is made before fork: after it, only async-signal-safe calls.
  std::vector<std::string> words{BEZINV_CLI_PATH};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    struct sigaction default_action {};
    default_action.sa_handler = SIG_DFL;
    for (const int signal_number : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) ::sigaction(signal_number, &default_action, nullptr);
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    const int out = ::open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out < 0 || err < 0 || ::dup2(out, STDOUT_FILENO) < 0 || ::dup2(err, STDERR_FILENO) < 0) ::_exit(126);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  EXPECT_GT(pid, 0) << std::strerror(errno);
  return pid;
}

// Waits for the child at most `limit`, then kills it.
Ended wait_bounded(pid_t pid, std::chrono::steady_clock::duration limit = kPatience) {
  Ended ended;
  if (pid <= 0) return ended;
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (true) {
    const pid_t done = ::wait4(pid, &ended.status, WNOHANG, &ended.usage);
    if (done == pid) {
      ended.in_time = true;
      return ended;
    }
    if (done < 0 || std::chrono::steady_clock::now() > deadline) break;
    std::this_thread::sleep_for(2ms);
  }
  ::kill(pid, SIGKILL);
  ::wait4(pid, &ended.status, 0, &ended.usage);
  return ended;
}

// Feeds `data` into a FIFO, then holds it open without closing, so the reader at the other end
// (bezinv's --points) waits for more: a run that is guaranteed to be in progress. Opened O_RDWR
// so that opening never waits and a reader that dies does not raise SIGPIPE here.
class FifoFeeder {
 public:
  FifoFeeder(const std::string& fifo, std::string data) : data_(std::move(data)) {
    fd_ = ::open(fifo.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
    EXPECT_GE(fd_, 0) << fifo << ": " << std::strerror(errno);
    if (fd_ >= 0) thread_ = std::thread([this] { feed(); });
  }
  ~FifoFeeder() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
    if (fd_ >= 0) ::close(fd_);
  }
  FifoFeeder(const FifoFeeder&) = delete;
  FifoFeeder& operator=(const FifoFeeder&) = delete;

 private:
  void feed() {
    std::size_t sent = 0;
    const auto deadline = std::chrono::steady_clock::now() + kPatience;
    while (!stop_ && sent < data_.size() && std::chrono::steady_clock::now() < deadline) {
      const ssize_t wrote = ::write(fd_, data_.data() + sent, data_.size() - sent);
      if (wrote > 0) {
        sent += static_cast<std::size_t>(wrote);
        continue;
      }
      pollfd ready{fd_, POLLOUT, 0};
      ::poll(&ready, 1, 20);
    }
  }

  std::string data_;
  int fd_ = -1;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// Everything written into a FIFO until its writer is gone, read while the writer runs (so a full
// pipe never blocks it). Opened non-blocking before the writer starts, so neither side waits to open.
class FifoDrain {
 public:
  explicit FifoDrain(const std::string& fifo) {
    fd_ = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    EXPECT_GE(fd_, 0) << fifo << ": " << std::strerror(errno);
    if (fd_ >= 0) thread_ = std::thread([this] { drain(); });
  }
  ~FifoDrain() { finish(); }
  FifoDrain(const FifoDrain&) = delete;
  FifoDrain& operator=(const FifoDrain&) = delete;

  // Call once the writer has exited: what it wrote.
  std::string finish() {
    writer_done_ = true;
    if (thread_.joinable()) thread_.join();
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    return received_;
  }

 private:
  void drain() {
    const auto deadline = std::chrono::steady_clock::now() + kPatience;
    char buffer[1 << 16];
    while (std::chrono::steady_clock::now() < deadline) {
      const ssize_t got = ::read(fd_, buffer, sizeof buffer);
      if (got > 0) {
        received_.append(buffer, static_cast<std::size_t>(got));
        continue;
      }
      // 0: no writer has it open (not yet, or no more); after the writer exited that is the end.
      if (got == 0 && writer_done_) return;
      pollfd ready{fd_, POLLIN, 0};
      if (::poll(&ready, 1, 20) > 0 && (ready.revents & POLLHUP) != 0 && !writer_done_) std::this_thread::sleep_for(2ms);
    }
  }

  int fd_ = -1;
  std::atomic<bool> writer_done_{false};
  std::string received_;
  std::thread thread_;
};

class CliOutput : public ::testing::Test {
 protected:
  ScratchDirectory scratch{"bezinv-cli-output-test-"};
  std::string curves = scratch.write("curves.json", kCubicJson);
  std::string points = scratch.write("points.csv", kPointsCsv);
  std::string points_npy = scratch.write("points.npy", four_points_npy());

  void SetUp() override {
    fs::create_directory(scratch.root() / "sub");
    reference_csv_ = reference(".csv");
    reference_npy_ = reference(".npy");
    ASSERT_EQ(split(reference_csv_, '\n').size(), 6u) << reference_csv_;  // header, 4 rows, ""
    ASSERT_TRUE(reference_csv_.starts_with("t,status,")) << reference_csv_;
    ASSERT_GT(reference_npy_.size(), 4 * 42u);
  }

  // The arguments of a run of the four CSV points (or .npy: the same points from points.npy).
  std::vector<std::string> invert_words(const std::string& out, bool npy_points = false) const {
    if (npy_points) return {"invert", "--curves", curves, "--points", points_npy, "--curve", "cubic", "--out", out};
    return {"invert", "--curves", curves, "--points", points, "--out", out};
  }

  Outcome run(const std::vector<std::string>& words) const {
    std::string arguments;
    for (const std::string& word : words) arguments += shell_quoted(word) + " ";
    return run_bezinv(scratch, arguments);
  }

  Outcome invert_to(const std::string& out, const std::string& extra = "") const {
    return run_bezinv(scratch, "invert --curves " + shell_quoted(curves) + " --points " + shell_quoted(points) + " --out " +
                                   shell_quoted(out) + " " + extra);
  }

  const std::string& expected(const std::string& out) const {
    return out.ends_with(".npy") ? reference_npy_ : reference_csv_;
  }

  void expect_no_temporaries() const {
    EXPECT_EQ(temporaries_in(scratch.root()), std::vector<std::string>{});
    EXPECT_EQ(temporaries_in(scratch.root() / "sub"), std::vector<std::string>{});
  }

  std::string reference_csv_, reference_npy_;

 private:
  std::string reference(const std::string& extension) {
    const std::string out = scratch.path("reference" + extension);
    const Outcome result = invert_to(out);
    EXPECT_EQ(result.exit_code, 0) << result.err;
    std::string bytes = read_file(out);
    fs::remove(out);
    return bytes;
  }
};

bool running_as_root() { return ::geteuid() == 0; }

// ---- OUT is an input --------------------------------------------------------------------------

TEST_F(CliOutput, RefusesOutThatIsAnInputUnderAnySpelling) {
  const std::string index = scratch.write("index.npy", npy_file("<i8", "(4,)", std::string(32, '\0')));
  fs::create_symlink("points.csv", scratch.root() / "points-link.csv");
  fs::create_hard_link(scratch.root() / "points.csv", scratch.root() / "points-hard.csv");
  fs::create_directory_symlink(scratch.root(), scratch.root() / "sub" / "up");
  fs::create_symlink(scratch.root() / "curves.json", scratch.root() / "curves-link.json");
  fs::create_hard_link(scratch.root() / "index.npy", scratch.root() / "index-hard.npy");
  fs::create_hard_link(scratch.root() / "points.npy", scratch.root() / "points-hard.npy");

  const std::string root = scratch.root().string();
  struct Case {
    std::string out;
    std::vector<std::string> words;  // without --out
    std::string input;               // the input OUT names, as given
  };
  const std::vector<std::string> csv_run{"invert", "--curves", curves, "--points", points};
  const std::vector<std::string> index_run{"invert", "--curves", curves, "--points", points_npy, "--curve-index", index};
  const std::vector<std::string> npy_run{"invert", "--curves", curves, "--points", points_npy, "--curve", "cubic"};
  const std::vector<Case> cases{
      {points, csv_run, points},
      {root + "/./points.csv", csv_run, points},
      {root + "/sub/../points.csv", csv_run, points},
      {root + "//points.csv", csv_run, points},
      {root + "/points-link.csv", csv_run, points},
      {root + "/points-hard.csv", csv_run, points},
      {root + "/sub/up/points.csv", csv_run, points},
      {curves, csv_run, curves},
      {root + "/curves-link.json", csv_run, curves},
      {root + "/sub/up/curves.json", csv_run, curves},
      {index, index_run, index},
      {root + "/index-hard.npy", index_run, index},
      {root + "/./points.npy", npy_run, points_npy},
      {root + "/points-hard.npy", npy_run, points_npy},
  };
  const std::vector<std::string> before = entries_of(scratch.root());
  for (const Case& c : cases) {
    const std::string input_bytes = read_file(c.input);
    const struct stat input_before = lstat_of(c.input);
    std::vector<std::string> words = c.words;
    words.insert(words.end(), {"--out", c.out});
    const Outcome result = run(words);
    EXPECT_EQ(result.exit_code, 2) << c.out << "\n" << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_TRUE(result.err.starts_with("bezinv: " + c.out + ": ")) << result.err;
    EXPECT_NE(result.err.find("same file as"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find(c.input), std::string::npos) << result.err;
    EXPECT_EQ(read_file(c.input), input_bytes) << c.input;
    EXPECT_EQ(lstat_of(c.input).st_ino, input_before.st_ino) << c.input;  // not replaced by an identical copy
    EXPECT_EQ(entries_of(scratch.root()), before) << c.out;                // no temporary, no new file
  }
}

TEST_F(CliOutput, RefusesOutThatIsAnInputSpelledRelativeToTheWorkingDirectory) {
  const std::string points_bytes = read_file(points);
  for (const char* spelling : {"points.csv", "./points.csv", "sub/../points.csv"}) {
    const std::string command = "cd " + shell_quoted(scratch.root().string()) + " && " + shell_quoted(BEZINV_CLI_PATH) +
                                " invert --curves curves.json --points points.csv --out " + spelling +
                                " 2>stderr.txt";
    const int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2) << spelling;
    const std::string err = read_file(scratch.path("stderr.txt"));
    EXPECT_EQ(err, "bezinv: " + std::string(spelling) +
                       ": --out is the same file as --points points.csv; refusing to overwrite an input\n");
    EXPECT_EQ(read_file(points), points_bytes);
  }
  expect_no_temporaries();
}

// ---- Regular files ------------------------------------------------------------------------------

TEST_F(CliOutput, NewOutGetsTheUmaskModeAndNoTemporaryRemains) {
  const mode_t saved = ::umask(027);
  for (const char* name : {"new.csv", "new.npy"}) {
    const std::string out = scratch.path(name);
    const Outcome result = invert_to(out);
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(read_file(out), expected(out)) << name;
    EXPECT_EQ(lstat_of(out).st_mode & 07777, 0640u) << name;
  }
  ::umask(saved);
  expect_no_temporaries();
}

TEST_F(CliOutput, ExistingOutKeepsItsMode) {
  for (const mode_t mode : {0600, 0640, 0604, 0755, 0444, 02750}) {
    for (const char* name : {"old.csv", "old.npy"}) {
      const std::string out = scratch.write(name, "stale contents\n");
      ASSERT_EQ(::chmod(out.c_str(), mode), 0);
      const Outcome result = invert_to(out);
      EXPECT_EQ(result.exit_code, 0) << result.err;
      EXPECT_EQ(read_file(out), expected(out)) << name;
      EXPECT_EQ(lstat_of(out).st_mode & 07777, mode) << name << " mode " << std::oct << mode;
      fs::remove(out);
    }
  }
  expect_no_temporaries();
}

TEST_F(CliOutput, ExistingOutKeepsItsOwnerWhenRunAsRoot) {
  if (!running_as_root()) GTEST_SKIP() << "only root can give a file to another user (and bezinv keeps it only as root)";
  constexpr uid_t kNobody = 65534;
  constexpr gid_t kNogroup = 65534;
  for (const char* name : {"owned.csv", "owned.npy"}) {
    const std::string out = scratch.write(name, "stale contents\n");
    ASSERT_EQ(::chown(out.c_str(), kNobody, kNogroup), 0) << std::strerror(errno);
    ASSERT_EQ(::chmod(out.c_str(), 0640), 0);
    const Outcome result = invert_to(out);
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(read_file(out), expected(out)) << name;
    const struct stat after = lstat_of(out);
    EXPECT_EQ(after.st_uid, kNobody) << name;
    EXPECT_EQ(after.st_gid, kNogroup) << name;
    EXPECT_EQ(after.st_mode & 07777, 0640u) << name;
  }
  expect_no_temporaries();
}

TEST_F(CliOutput, HardLinkedOutIsRewrittenInPlaceForEveryLink) {
  // Old contents longer and shorter than the results: the file is cut to the new length.
  for (const std::string& old : {std::string(100000, 'x'), std::string("x\n")}) {
    for (const char* name : {"linked.csv", "linked.npy"}) {
      const std::string out = scratch.write(name, old);
      const fs::path other = scratch.root() / "sub" / (std::string("other-") + name);
      fs::create_hard_link(out, other);
      ASSERT_EQ(::chmod(out.c_str(), 0620), 0);
      const struct stat before = lstat_of(out);
      const Outcome result = invert_to(out);
      EXPECT_EQ(result.exit_code, 0) << result.err;
      const struct stat after = lstat_of(out);
      EXPECT_EQ(after.st_ino, before.st_ino) << name;  // the same file, not a new one
      EXPECT_EQ(after.st_nlink, 2u) << name;
      EXPECT_EQ(after.st_mode & 07777, 0620u) << name;
      EXPECT_EQ(lstat_of(other.string()).st_ino, before.st_ino) << name;
      EXPECT_EQ(read_file(out), expected(out)) << name;
      EXPECT_EQ(read_file(other.string()), expected(out)) << name;
      fs::remove(out);
      fs::remove(other);
    }
  }
  expect_no_temporaries();
}

// ---- Symbolic links ---------------------------------------------------------------------------

TEST_F(CliOutput, SymlinkStaysALinkAndItsTargetGetsTheRows) {
  const std::string root = scratch.root().string();
  struct Case {
    std::string link, link_text, target;
  };
  const std::vector<Case> cases{
      {"rel.csv", "sub/target.csv", root + "/sub/target.csv"},
      {"abs.csv", root + "/sub/abs-target.csv", root + "/sub/abs-target.csv"},
      {"rel.npy", "sub/target.npy", root + "/sub/target.npy"},
      {"sub/up.csv", "../up-target.csv", root + "/up-target.csv"},
  };
  for (const Case& c : cases) {
    const std::string target = scratch.write(fs::relative(c.target, root).string(), "stale contents\n");
    ASSERT_EQ(::chmod(target.c_str(), 0600), 0);
    const std::string link = scratch.path(c.link);
    fs::create_symlink(c.link_text, link);
    const Outcome result = invert_to(link);
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_TRUE(S_ISLNK(lstat_of(link).st_mode)) << c.link;
    EXPECT_EQ(fs::read_symlink(link).string(), c.link_text) << c.link;
    EXPECT_EQ(read_file(target), expected(link)) << c.link;
    EXPECT_EQ(lstat_of(target).st_mode & 07777, 0600u) << c.link;
  }
  // A chain of links: the last one's target is written.
  fs::create_symlink("chain-2.csv", scratch.root() / "chain-1.csv");
  fs::create_symlink("sub/chain-target.csv", scratch.root() / "chain-2.csv");
  const std::string chain_target = scratch.write("sub/chain-target.csv", "stale\n");
  EXPECT_EQ(invert_to(scratch.path("chain-1.csv")).exit_code, 0);
  EXPECT_TRUE(S_ISLNK(lstat_of(scratch.path("chain-1.csv")).st_mode));
  EXPECT_TRUE(S_ISLNK(lstat_of(scratch.path("chain-2.csv")).st_mode));
  EXPECT_EQ(read_file(chain_target), reference_csv_);
  expect_no_temporaries();
}

TEST_F(CliOutput, DanglingSymlinkGetsItsTargetCreated) {
  fs::create_symlink("sub/new.csv", scratch.root() / "dangling.csv");
  fs::create_symlink("sub/new.npy", scratch.root() / "dangling.npy");
  fs::create_symlink("dangling-2.csv", scratch.root() / "dangling-1.csv");
  fs::create_symlink(scratch.path("sub/new-2.csv"), scratch.root() / "dangling-2.csv");
  for (const auto& [link, target] : {std::pair{"dangling.csv", "sub/new.csv"}, std::pair{"dangling.npy", "sub/new.npy"},
                                     std::pair{"dangling-1.csv", "sub/new-2.csv"}}) {
    const Outcome result = invert_to(scratch.path(link));
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_TRUE(S_ISLNK(lstat_of(scratch.path(link)).st_mode)) << link;
    EXPECT_TRUE(S_ISREG(lstat_of(scratch.path(target)).st_mode)) << target;
    EXPECT_EQ(read_file(scratch.path(target)), expected(link)) << link;
  }
  // Into a directory that does not exist: refused, naming the link and where it points.
  fs::create_symlink("missing/out.csv", scratch.root() / "nowhere.csv");
  const Outcome result = invert_to(scratch.path("nowhere.csv"));
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_TRUE(result.err.starts_with("bezinv: " + scratch.path("nowhere.csv"))) << result.err;
  EXPECT_NE(result.err.find("missing/out.csv"), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(scratch.root() / "missing"));
  expect_no_temporaries();
}

// ---- Devices and FIFOs: written through ---------------------------------------------------------

// A character device node in the scratch directory, the same device as /dev/<name>: the test
// checks the node the run was given, and never risks the system's own.
std::string make_device(const ScratchDirectory& scratch, const std::string& name, unsigned minor) {
  const std::string path = scratch.path(name);
  if (::mknod(path.c_str(), S_IFCHR | 0666, makedev(1, minor)) != 0) return "";
  return path;
}

TEST_F(CliOutput, CharacterDeviceIsWrittenThroughAndStaysADevice) {
  if (!running_as_root()) GTEST_SKIP() << "creating a device node (mknod) needs root";
  const std::string null_device = make_device(scratch, "null", 3);
  if (null_device.empty()) GTEST_SKIP() << "mknod refused here (" << std::strerror(errno) << "), e.g. a container without CAP_MKNOD";
  fs::create_symlink("null", scratch.root() / "null.npy");  // .npy to a device that can seek
  fs::create_symlink("null", scratch.root() / "null-link.csv");
  for (const char* name : {"null", "null.npy", "null-link.csv"}) {
    const Outcome result = invert_to(scratch.path(name));
    EXPECT_EQ(result.exit_code, 0) << name << ": " << result.err;
    const struct stat after = lstat_of(null_device);
    EXPECT_TRUE(S_ISCHR(after.st_mode)) << name;
    EXPECT_EQ(after.st_rdev, makedev(1, 3)) << name;
  }
  EXPECT_TRUE(S_ISLNK(lstat_of(scratch.path("null.npy")).st_mode));
  expect_no_temporaries();

  // /dev/full fails every write: a run that went through a temporary would succeed instead.
  const std::string full_device = make_device(scratch, "full", 7);
  ASSERT_FALSE(full_device.empty()) << std::strerror(errno);
  const Outcome full = invert_to(full_device);
  EXPECT_EQ(full.exit_code, 2) << full.err;
  EXPECT_EQ(full.err, "bezinv: " + full_device + ": cannot write: " + std::strerror(ENOSPC) + "\n");
  EXPECT_TRUE(S_ISCHR(lstat_of(full_device).st_mode));
  expect_no_temporaries();
}

TEST_F(CliOutput, DevNullStaysADevice) {
  if (!running_as_root()) GTEST_SKIP() << "as another user /dev is not writable, so /dev/null could not be replaced anyway";
  const struct stat before = lstat_of("/dev/null");
  ASSERT_TRUE(S_ISCHR(before.st_mode));
  const Outcome result = invert_to("/dev/null");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
  const struct stat after = lstat_of("/dev/null");
  EXPECT_TRUE(S_ISCHR(after.st_mode));
  EXPECT_EQ(after.st_rdev, before.st_rdev);
  EXPECT_EQ(after.st_ino, before.st_ino);
  EXPECT_EQ(temporaries_in("/dev"), std::vector<std::string>{});
}

TEST_F(CliOutput, FifoReaderReceivesTheRowsAndTheFifoStays) {
  const std::string fifo = scratch.path("results.fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  fs::create_symlink("results.fifo", scratch.root() / "fifo-link.csv");
  for (const std::string& out : {fifo, scratch.path("fifo-link.csv")}) {
    FifoDrain drain(fifo);
    const pid_t pid = spawn_bezinv(invert_words(out), scratch.path("stdout.txt"), scratch.path("stderr.txt"));
    const Ended ended = wait_bounded(pid);
    const std::string received = drain.finish();
    ASSERT_TRUE(ended.in_time) << out;
    EXPECT_TRUE(WIFEXITED(ended.status) && WEXITSTATUS(ended.status) == 0) << read_file(scratch.path("stderr.txt"));
    EXPECT_EQ(received, reference_csv_) << out;
    EXPECT_TRUE(S_ISFIFO(lstat_of(fifo).st_mode)) << out;
  }
  EXPECT_TRUE(S_ISLNK(lstat_of(scratch.path("fifo-link.csv")).st_mode));
  expect_no_temporaries();
}

TEST_F(CliOutput, NpyToAFifoIsRefused) {
  const std::string fifo = scratch.path("results.npy");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  FifoDrain drain(fifo);  // so that a build that opens the FIFO anyway does not wait for a reader
  const pid_t pid = spawn_bezinv(invert_words(fifo), scratch.path("stdout.txt"), scratch.path("stderr.txt"));
  const Ended ended = wait_bounded(pid);
  EXPECT_EQ(drain.finish(), "");
  ASSERT_TRUE(ended.in_time);
  EXPECT_TRUE(WIFEXITED(ended.status) && WEXITSTATUS(ended.status) == 2);
  const std::string err = read_file(scratch.path("stderr.txt"));
  EXPECT_TRUE(err.starts_with("bezinv: " + fifo + ": cannot write a .npy to a FIFO")) << err;
  EXPECT_TRUE(S_ISFIFO(lstat_of(fifo).st_mode));
  expect_no_temporaries();
}

TEST_F(CliOutput, DirectoryIsRefused) {
  const Outcome result = invert_to(scratch.path("sub"));
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(result.err, "bezinv: " + scratch.path("sub") + ": cannot write: is a directory\n");
  EXPECT_TRUE(fs::is_directory(scratch.root() / "sub"));
  expect_no_temporaries();
}

// ---- A failed run ------------------------------------------------------------------------------

TEST_F(CliOutput, FailedRunLeavesEveryKindOfOutAsItWas) {
  // Three good rows, then one that fails the whole file: met after OUT was opened.
  const std::string bad_points = scratch.write("bad.csv", std::string(kPointsCsv) + "cubic,1\n");
  const std::string old = "old results\n";
  const std::string regular = scratch.write("regular.csv", old);
  ASSERT_EQ(::chmod(regular.c_str(), 0640), 0);
  const std::string linked = scratch.write("linked.csv", old);
  fs::create_hard_link(linked, scratch.root() / "sub" / "linked-other.csv");
  const std::string target = scratch.write("sub/target.npy", old);
  fs::create_symlink("sub/target.npy", scratch.root() / "link.npy");
  for (const std::string& out : {regular, linked, scratch.path("link.npy"), scratch.path("absent.csv")}) {
    const bool absent = out.ends_with("absent.csv");
    const std::string file = out.ends_with("link.npy") ? target : out;  // what OUT names
    struct stat before {};
    if (!absent) before = lstat_of(file);
    const Outcome result = run_bezinv(scratch, "invert --curves " + shell_quoted(curves) + " --points " + shell_quoted(bad_points) +
                                                   " --out " + shell_quoted(out));
    EXPECT_EQ(result.exit_code, 2) << out;
    EXPECT_NE(result.err.find("bad.csv:6"), std::string::npos) << result.err;
    if (absent) {
      EXPECT_FALSE(fs::exists(out));
      continue;
    }
    EXPECT_EQ(read_file(file), old) << out;
    const struct stat after = lstat_of(file);
    EXPECT_EQ(after.st_ino, before.st_ino) << out;
    EXPECT_EQ(after.st_mode, before.st_mode) << out;
  }
  EXPECT_EQ(read_file(scratch.path("sub/linked-other.csv")), old);
  EXPECT_TRUE(S_ISLNK(lstat_of(scratch.path("link.npy")).st_mode));
  expect_no_temporaries();
}

// ---- Signals ---------------------------------------------------------------------------------

enum class Existing { none, regular, hard_linked };

class CliOutputSignal : public CliOutput, public ::testing::WithParamInterface<std::tuple<int, const char*, Existing>> {};

// The points come through a FIFO that is fed 6.5 MB of rows (more than the CSV reader's 4 MB block)
// and then held open: bezinv has created its temporary and waits for more points, however fast
// the machine, when the signal arrives.
TEST_P(CliOutputSignal, RemovesTheTemporaryAndDiesByTheSignal) {
  const auto [signal_number, extension, existing] = GetParam();
  const std::string fifo = scratch.path("points.fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  const std::string out = scratch.path(std::string("out") + extension);
  const std::string old = "results of an earlier run\n";
  if (existing != Existing::none) scratch.write(std::string("out") + extension, old);
  if (existing == Existing::hard_linked) fs::create_hard_link(out, scratch.root() / "sub" / "other");
  const std::vector<std::string> before = entries_of(scratch.root());

  FifoFeeder feeder(fifo, cubic_points_csv(150000));
  std::vector<std::string> words = invert_words(out);
  words[4] = fifo;
  const pid_t pid = spawn_bezinv(words, scratch.path("stdout.txt"), scratch.path("stderr.txt"));
  ASSERT_GT(pid, 0);
  const auto deadline = std::chrono::steady_clock::now() + kPatience;
  while (temporaries_in(scratch.root()).empty() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(1ms);
  EXPECT_EQ(temporaries_in(scratch.root()).size(), 1u) << "bezinv never created its temporary";
  ::kill(pid, signal_number);
  const Ended ended = wait_bounded(pid);
  ASSERT_TRUE(ended.in_time) << "bezinv did not end on the signal";
  EXPECT_TRUE(WIFSIGNALED(ended.status)) << "status " << ended.status;
  if (WIFSIGNALED(ended.status)) {
    EXPECT_EQ(WTERMSIG(ended.status), signal_number);
  }
  EXPECT_EQ(read_file(scratch.path("stderr.txt")), "");

  expect_no_temporaries();
  EXPECT_EQ(entries_of(scratch.root()), before);
  if (existing == Existing::none) {
    EXPECT_FALSE(fs::exists(out));
  } else {
    EXPECT_EQ(read_file(out), old);
  }
  if (existing == Existing::hard_linked) {
    EXPECT_EQ(read_file(scratch.path("sub/other")), old);
  }
}

std::string signal_case_name(const ::testing::TestParamInfo<CliOutputSignal::ParamType>& info) {
  const auto [signal_number, extension, existing] = info.param;
  const char* signal_name = signal_number == SIGINT ? "Sigint" : signal_number == SIGTERM ? "Sigterm" : "Sighup";
  const char* kind = existing == Existing::none ? "NoOut" : existing == Existing::regular ? "ExistingOut" : "HardLinkedOut";
  return std::string(signal_name) + (std::string(extension) == ".npy" ? "Npy" : "Csv") + kind;
}

INSTANTIATE_TEST_SUITE_P(EverySignal, CliOutputSignal,
                         ::testing::Combine(::testing::Values(SIGINT, SIGTERM, SIGHUP), ::testing::Values(".csv", ".npy"),
                                            ::testing::Values(Existing::none, Existing::regular, Existing::hard_linked)),
                         signal_case_name);

// A plain big input file, as a user would run it: the signal lands while rows are being inverted
// and written.
TEST_F(CliOutput, SignalDuringARunOnABigFileLeavesNothing) {
  const std::string big = write_cubic_points_npy(scratch.path("big.npy"), 4000000);
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
    const std::string out = scratch.path("big-out.npy");
    const pid_t pid = spawn_bezinv({"invert", "--curves", curves, "--points", big, "--curve", "cubic", "--out", out,
                                    "--svd-only", "--threads", "1", "--chunk-points", "65536"},
                                   scratch.path("stdout.txt"), scratch.path("stderr.txt"));
    ASSERT_GT(pid, 0);
    // Once the temporary has some rows in it, the run is well under way.
    const auto deadline = std::chrono::steady_clock::now() + kPatience;
    while (std::chrono::steady_clock::now() < deadline) {
      const std::vector<std::string> found = temporaries_in(scratch.root());
      std::error_code error;
      if (!found.empty() && fs::file_size(found.front(), error) > (1u << 20)) break;
      std::this_thread::sleep_for(1ms);
    }
    ::kill(pid, signal_number);
    const Ended ended = wait_bounded(pid);
    ASSERT_TRUE(ended.in_time);
    if (WIFEXITED(ended.status) && WEXITSTATUS(ended.status) == 0)
      GTEST_SKIP() << "this machine inverted 4,000,000 points before the signal arrived";
    EXPECT_TRUE(WIFSIGNALED(ended.status) && WTERMSIG(ended.status) == signal_number) << "status " << ended.status;
    EXPECT_FALSE(fs::exists(out));
    expect_no_temporaries();
  }
}

// ---- --threads and --chunk-points bounds ---------------------------------------------------

TEST_F(CliOutput, ThreadsAboveTheBoundAreAnInputError) {
  const std::string out = scratch.path("out.csv");
  for (const char* threads : {"1025", "100000", "4294967296"}) {
    for (const std::string& command :
         {"invert --curves " + shell_quoted(curves) + " --points " + shell_quoted(points) + " --out " + shell_quoted(out),
          std::string("demo --points 10"), std::string("profile --points 10")}) {
      const Outcome result = run_bezinv(scratch, command + " --threads " + threads);
      EXPECT_EQ(result.exit_code, 2) << command << " --threads " << threads << "\n" << result.err;
      EXPECT_EQ(result.err, "bezinv: --threads " + std::string(threads) + ": at most 1024 (0: all cores)\n");
      EXPECT_EQ(result.out, "");
    }
  }
  EXPECT_FALSE(fs::exists(out));
  const Outcome help = run_bezinv(scratch, "invert --help");
  EXPECT_NE(help.out.find("at most 1024"), std::string::npos) << help.out;
}

TEST_F(CliOutput, ThreadsUpToTheBoundRunQuietly) {
  // More threads than cores: TBB must not print its "number of workers is limited" warning.
  for (const char* threads : {"1", "64", "1024"}) {
    const std::string out = scratch.path("out.csv");
    const Outcome result = invert_to(out, std::string("--threads ") + threads);
    EXPECT_EQ(result.exit_code, 0) << threads;
    EXPECT_EQ(result.err, "") << threads;
    EXPECT_EQ(read_file(out), reference_csv_) << threads;
  }
}

TEST_F(CliOutput, ChunkPointsAboveTheBoundAreAnInputError) {
  const std::string out = scratch.path("out.csv");
  for (const char* chunk : {"16777217", "50000000"}) {
    const Outcome result = invert_to(out, std::string("--chunk-points ") + chunk);
    EXPECT_EQ(result.exit_code, 2) << result.err;
    EXPECT_EQ(result.err, "bezinv: --chunk-points " + std::string(chunk) +
                              ": at most 16777216 (about 100 bytes of memory per point)\n");
  }
  EXPECT_FALSE(fs::exists(out));
}

// The largest chunk on a small input allocates for the input, not for the chunk (16777216 points
// would be about 1.7 GB).
TEST_F(CliOutput, LargestChunkOnASmallInputTakesLittleMemory) {
  for (const bool npy_points : {false, true}) {
    const std::string out = scratch.path("out.csv");
    std::vector<std::string> words = invert_words(out, npy_points);
    words.insert(words.end(), {"--chunk-points", "16777216"});
    const Ended ended = wait_bounded(spawn_bezinv(words, scratch.path("stdout.txt"), scratch.path("stderr.txt")));
    ASSERT_TRUE(ended.in_time);
    EXPECT_TRUE(WIFEXITED(ended.status) && WEXITSTATUS(ended.status) == 0) << read_file(scratch.path("stderr.txt"));
    EXPECT_EQ(read_file(out), reference_csv_);
    // In KB: this takes a few tens of MB (more under the sanitizers), the whole chunk 1.8 GB.
    EXPECT_LT(ended.usage.ru_maxrss, 400 * 1024) << "peak resident set in KB, npy points " << npy_points;
  }
}

// Chunks that grow as the input keeps filling them give the same file as any fixed chunk size.
TEST_F(CliOutput, EveryChunkSizeGivesTheSameResults) {
  // Past the first buffer (65536 points) and its doubling; chunks of 1 point are Stream.*'s.
  const std::string csv = scratch.write("many.csv", cubic_points_csv(70000));
  const std::string npy = scratch.write("many.npy", cubic_points_npy(70000));
  // Under the sanitizers (support/sanitizers.hpp) each chunk size is tried with one of the two
  // inputs, in turn.
  const std::array<const char*, 6> chunks = {"7", "65535", "65536", "65537", "131072", "16777216"};
  for (std::size_t input_index = 0; input_index < 2; ++input_index) {
    const std::string& input = input_index == 0 ? csv : npy;
    const std::string base = "invert --curves " + shell_quoted(curves) + " --points " + shell_quoted(input) +
                             (input.ends_with(".npy") ? " --curve cubic" : "");
    const std::string reference_out = scratch.path("many-reference.csv");
    ASSERT_EQ(run_bezinv(scratch, base + " --out " + shell_quoted(reference_out)).exit_code, 0);
    const std::string reference = read_file(reference_out);
    EXPECT_EQ(split(reference, '\n').size(), 70002u);
    for (std::size_t chunk_index = 0; chunk_index < chunks.size(); ++chunk_index) {
      if (bezinv::test_support::kSanitizerTree && (input_index + chunk_index) % 2 != 0) continue;
      const char* chunk = chunks[chunk_index];
      const std::string out = scratch.path("many-out.csv");
      const Outcome result = run_bezinv(scratch, base + " --out " + shell_quoted(out) + " --chunk-points " + chunk);
      EXPECT_EQ(result.exit_code, 0) << result.err;
      EXPECT_TRUE(read_file(out) == reference) << input << " --chunk-points " << chunk;
    }
  }
}

}  // namespace
