// A main() for the libFuzzer targets of this folder where libFuzzer is not: the GCC sanitizer tree
// of scripts/test.sh. It runs every seed of the corpus, then random mutations of the seeds for a
// fixed time. It is blind (no coverage feedback: the coverage-guided runs are the clang tree's,
// scripts/fuzz.sh), but it runs each target's own contract checks under GCC's ASan and UBSan on
// every build, on inputs the seeds alone never reach. Deterministic: the same seed (--seed) and the
// same corpus give the same inputs, and the input that fails is written out to be replayed.
//
//   TARGET [--seconds S] [--runs N] [--seed N] [--dict FILE] [--artifact-prefix P] CORPUS_DIR_OR_FILE...
//
// It stops after S seconds (default 5) or N inputs in all, whichever comes first. With --seconds 0
// it replays the files given (a failing input: TARGET --seconds 0 FILE).
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sanitizer/common_interface_defs.h>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

using Bytes = std::vector<std::uint8_t>;

// libFuzzer's default -max_len for a corpus of small seeds is 4096; a little more lets splices grow.
constexpr std::size_t kMaxInputSize = 8192;

// The input being run, for the handlers that write it out when it fails.
const Bytes* g_current = nullptr;
std::string g_artifact_path;
std::string g_artifact_message;  // made before any input runs: the handlers only write it

// Async-signal-safe: open, write, close only.
void write_current_input() {
  if (g_current == nullptr) return;
  const int fd = ::open(g_artifact_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) return;
  std::size_t done = 0;
  while (done < g_current->size()) {
    const ssize_t n = ::write(fd, g_current->data() + done, g_current->size() - done);
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
  [[maybe_unused]] const ssize_t ignored = ::write(2, g_artifact_message.data(), g_artifact_message.size());
}

// A sanitizer's report ends in its death callback; a contract check (__builtin_trap) in SIGILL;
// an abort() in SIGABRT. Each writes the input, then dies as it would have.
void on_signal(int signal_number) {
  write_current_input();
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

Bytes read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// libFuzzer's dictionary format: one "token" per line (optionally name="token"), with \\, \" and
// \xNN escapes; # starts a comment.
std::vector<Bytes> read_dictionary(const std::string& path) {
  std::vector<Bytes> tokens;
  std::ifstream in(path);
  if (!in) {
    std::fprintf(stderr, "mutation_driver: cannot read the dictionary %s\n", path.c_str());
    std::exit(2);
  }
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t open = line.find('"');
    const std::size_t close = line.rfind('"');
    if (line.empty() || line[0] == '#' || open == std::string::npos || close <= open) continue;
    Bytes token;
    for (std::size_t i = open + 1; i < close; ++i) {
      if (line[i] != '\\' || i + 1 >= close) {
        token.push_back(static_cast<std::uint8_t>(line[i]));
      } else if (line[i + 1] == 'x' && i + 3 < close) {
        token.push_back(static_cast<std::uint8_t>(std::stoi(line.substr(i + 2, 2), nullptr, 16)));
        i += 3;
      } else {
        token.push_back(static_cast<std::uint8_t>(line[++i]));
      }
    }
    if (!token.empty()) tokens.push_back(std::move(token));
  }
  return tokens;
}

class Mutator {
 public:
  Mutator(std::uint64_t seed, const std::vector<Bytes>& seeds, const std::vector<Bytes>& dictionary)
      : random_(seed), seeds_(seeds), dictionary_(dictionary) {}

  // One to four of libFuzzer's kinds of mutation on a copy of a random seed.
  Bytes next() {
    Bytes input = seeds_[below(seeds_.size())];
    const std::size_t count = 1 + below(4);
    for (std::size_t k = 0; k < count; ++k) mutate(input);
    if (input.size() > kMaxInputSize) input.resize(kMaxInputSize);
    return input;
  }

 private:
  std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(random_() % n); }

  // Bytes that parsers branch on: digits, signs, separators, quotes, ends of lines, extremes.
  std::uint8_t interesting_byte() {
    static constexpr char kBytes[] = "0123456789+-.eE,;\"'[]{}:\n\r\t nN";
    switch (below(3)) {
      case 0: return static_cast<std::uint8_t>(kBytes[below(sizeof kBytes - 1)]);
      case 1: return static_cast<std::uint8_t>(below(2) ? 0x00 : 0xff);
      default: return static_cast<std::uint8_t>(below(256));
    }
  }

  void mutate(Bytes& b) {
    const std::size_t where = below(b.size() + 1);
    switch (below(8)) {
      case 0:  // flip a bit
        if (!b.empty()) b[below(b.size())] ^= static_cast<std::uint8_t>(1u << below(8));
        break;
      case 1:  // set a byte
        if (!b.empty()) b[below(b.size())] = interesting_byte();
        break;
      case 2:  // insert a byte
        b.insert(b.begin() + static_cast<std::ptrdiff_t>(where), interesting_byte());
        break;
      case 3: {  // erase a range
        if (b.empty()) break;
        const std::size_t first = below(b.size());
        const std::size_t length = 1 + below(std::min<std::size_t>(b.size() - first, 16));
        b.erase(b.begin() + static_cast<std::ptrdiff_t>(first), b.begin() + static_cast<std::ptrdiff_t>(first + length));
        break;
      }
      case 4: {  // repeat a range of the input at another place
        if (b.empty()) break;
        const std::size_t first = below(b.size());
        const std::size_t length = 1 + below(std::min<std::size_t>(b.size() - first, 64));
        const Bytes piece(b.begin() + static_cast<std::ptrdiff_t>(first), b.begin() + static_cast<std::ptrdiff_t>(first + length));
        b.insert(b.begin() + static_cast<std::ptrdiff_t>(where), piece.begin(), piece.end());
        break;
      }
      case 5: {  // splice: this input's head, another seed's tail
        const Bytes& other = seeds_[below(seeds_.size())];
        const std::size_t from = below(other.size() + 1);
        b.resize(where);
        b.insert(b.end(), other.begin() + static_cast<std::ptrdiff_t>(from), other.end());
        break;
      }
      case 6: {  // a dictionary word (or the ASCII of a random number where there is no dictionary)
        if (!dictionary_.empty()) {
          const Bytes& token = dictionary_[below(dictionary_.size())];
          b.insert(b.begin() + static_cast<std::ptrdiff_t>(where), token.begin(), token.end());
          break;
        }
        [[fallthrough]];
      }
      default: {  // a number, written out
        static constexpr const char* kNumbers[] = {"0", "-0", "1e308", "-1e308", "4.9e-324", "1e-300", "2.5",
                                                   "nan", "inf", "-inf", "18446744073709551616", "-1", "1e999"};
        const std::string number = kNumbers[below(std::size(kNumbers))];
        b.insert(b.begin() + static_cast<std::ptrdiff_t>(where), number.begin(), number.end());
        break;
      }
    }
  }

  std::mt19937_64 random_;
  const std::vector<Bytes>& seeds_;
  const std::vector<Bytes>& dictionary_;
};

int usage() {
  std::fprintf(stderr,
               "usage: TARGET [--seconds S] [--runs N] [--seed N] [--dict FILE] [--artifact-prefix P] "
               "CORPUS_DIR_OR_FILE...\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 5;
  std::uint64_t seed = 1;
  std::uint64_t max_runs = UINT64_MAX;
  std::string dictionary_path, artifact_prefix = "./";
  std::vector<std::filesystem::path> inputs;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--seconds" && has_value) seconds = std::strtod(argv[++i], nullptr);
    else if (arg == "--runs" && has_value) max_runs = std::strtoull(argv[++i], nullptr, 10);
    else if (arg == "--seed" && has_value) seed = std::strtoull(argv[++i], nullptr, 10);
    else if (arg == "--dict" && has_value) dictionary_path = argv[++i];
    else if (arg == "--artifact-prefix" && has_value) artifact_prefix = argv[++i];
    else if (!arg.empty() && arg[0] == '-') return usage();
    else inputs.emplace_back(arg);
  }
  if (inputs.empty() || !(seconds >= 0)) return usage();

  // The seeds, in name order (directory order is the file system's).
  std::vector<std::filesystem::path> files;
  for (const std::filesystem::path& input : inputs) {
    std::error_code error;
    if (std::filesystem::is_directory(input, error)) {
      for (const auto& entry : std::filesystem::directory_iterator(input))
        if (entry.is_regular_file()) files.push_back(entry.path());
    } else if (std::filesystem::is_regular_file(input, error)) {
      files.push_back(input);
    } else {
      std::fprintf(stderr, "mutation_driver: %s is neither a file nor a directory\n", input.c_str());
      return 2;
    }
  }
  std::sort(files.begin(), files.end());
  std::vector<Bytes> seeds;
  for (const std::filesystem::path& file : files) seeds.push_back(read_file(file));
  if (seeds.empty()) seeds.emplace_back();  // an empty corpus: mutate the empty input
  const std::vector<Bytes> dictionary = dictionary_path.empty() ? std::vector<Bytes>{} : read_dictionary(dictionary_path);

  g_artifact_path = artifact_prefix + "crash-seed" + std::to_string(seed);
  g_artifact_message = "\nmutation_driver: the failing input is in " + g_artifact_path + " (replay: " + argv[0] +
                       " --seconds 0 " + g_artifact_path + ")\n";
  __sanitizer_set_death_callback(write_current_input);
  ::signal(SIGILL, on_signal);
  ::signal(SIGABRT, on_signal);

  std::uint64_t runs = 0;
  for (const Bytes& input : seeds) {
    g_current = &input;
    LLVMFuzzerTestOneInput(input.data(), input.size());
    ++runs;
  }
  Mutator mutator(seed, seeds, dictionary);
  const auto start = std::chrono::steady_clock::now();
  const auto deadline = start + std::chrono::duration<double>(seconds);
  auto next_report = start + std::chrono::minutes(1);
  for (auto now = start; runs < max_runs && now < deadline; now = std::chrono::steady_clock::now()) {
    if (now >= next_report) {  // a long run says how far it is, once a minute
      std::printf("mutation_driver: %llu inputs in %.0f s\n", static_cast<unsigned long long>(runs),
                  std::chrono::duration<double>(now - start).count());
      std::fflush(stdout);
      next_report += std::chrono::minutes(1);
    }
    const Bytes input = mutator.next();
    g_current = &input;
    LLVMFuzzerTestOneInput(input.data(), input.size());
    ++runs;
  }
  g_current = nullptr;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("mutation_driver: %zu seeds and %llu inputs in all in %.0f s, seed %llu, no failure\n", seeds.size(),
              static_cast<unsigned long long>(runs), elapsed, static_cast<unsigned long long>(seed));
  return 0;
}
