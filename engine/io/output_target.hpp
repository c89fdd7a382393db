#pragma once
// Where the results go (engine internal): OUT written so that a failed or interrupted run leaves
// it as it was, and nothing but OUT's content changes (README "Where OUT goes").
//
//   OUT missing, or a regular file with one link: rows go to OUT.tmp.<pid>.<n> beside it, renamed
//     over OUT at commit (atomic within a directory); an existing OUT's mode is given to the new
//     file (and its owner, when running as root).
//   a regular file with several hard links: the same temporary, copied into OUT in place at
//     commit, so every link sees the new content.
//   a symbolic link: all of the above for the file it points to (the link stays a link); a
//     dangling link gets its target created.
//   a character device or a FIFO (/dev/null, a named pipe): written straight through, no temporary.
//   anything else (a directory, a block device, a socket): refused.
//
// The temporary file is removed when the writer is destroyed without commit(), and, once
// remove_temporary_outputs_on_signals() was called, when SIGINT, SIGTERM or SIGHUP ends the process.
#include <cstdio>
#include <string>
#include <string_view>

namespace bezinv::detail {

[[noreturn]] void fail_to_write(const std::string& path, int error);

class OutputTarget {
 public:
  // needs_seek: the caller will rewrite(); a pipe or terminal is refused then (InputError).
  OutputTarget(const std::string& path, bool needs_seek);
  OutputTarget(const OutputTarget&) = delete;
  OutputTarget& operator=(const OutputTarget&) = delete;
  ~OutputTarget();

  void write(std::string_view bytes);

  // Overwrites bytes already written at `offset` (the .npy header's row count), then carries on
  // at the end.
  void rewrite(long offset, std::string_view bytes);

  // Publishes what was written (see the table above). Throws InputError on failure, leaving a
  // regular OUT as it was.
  void commit();

 private:
  enum class Kind { replace, in_place, through };

  void open(bool needs_seek);
  void open_temporary(bool existing);
  void replace_target();
  void copy_into_target();
  void discard();

  std::string path_;       // as given, for messages
  std::string target_;     // the file written: path_ with symbolic links resolved
  std::string temporary_;  // empty when writing through
  Kind kind_ = Kind::replace;
  std::FILE* file_ = nullptr;  // the temporary, or the target when writing through
  int target_fd_ = -1;         // in_place: the target, opened early so a read-only OUT fails first
  int signal_slot_ = -1;       // where the signal handler finds temporary_, -1 if not registered
  bool committed_ = false;
};

}  // namespace bezinv::detail
