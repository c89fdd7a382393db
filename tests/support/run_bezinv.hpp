#pragma once
// Runs the real `bezinv` command (its path is BEZINV_CLI_PATH, from tests/CMakeLists.txt) for the
// end-to-end tests, capturing exit code, stdout and stderr.
#include <sys/wait.h>

#include <cstdlib>
#include <string>

#include "support/scratch_directory.hpp"

#ifndef BEZINV_CLI_PATH
#error "BEZINV_CLI_PATH must name the bezinv binary (tests/CMakeLists.txt defines it)"
#endif

namespace bezinv::test_support {

struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

// `arguments` must already be shell-quoted where needed (see quoted()). `environment`, e.g.
// "BEZINV_KERNEL=scalar", is set for this run only.
inline Outcome run_bezinv(const ScratchDirectory& scratch, const std::string& arguments,
                          const std::string& environment = "") {
  const std::string out = scratch.path("stdout.txt"), err = scratch.path("stderr.txt");
  const std::string command = (environment.empty() ? std::string() : "env " + environment + " ") + "'" +
                              BEZINV_CLI_PATH + "' " + arguments + " >'" + out + "' 2>'" + err + "'";
  const int status = std::system(command.c_str());
  Outcome run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = read_file(out);
  run.err = read_file(err);
  return run;
}

inline std::string quoted(const std::string& path) { return "'" + path + "'"; }

}  // namespace bezinv::test_support
