// Runs the built `pbm` (or any command) and collects its exit code and output (stdout + stderr).
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace pbm::test {

struct CliResult {
  int code = -1;
  std::string output;
};

// Runs a shell command line, stdout and stderr together.
inline CliResult run_command(const std::string& cmd) {
  CliResult r;
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  char buf[4096];
  while (std::fgets(buf, sizeof buf, pipe)) r.output += buf;
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline CliResult run_pbm(const std::string& args) {
  return run_command(std::string(PBM_BINARY_DIR) + "/app/pbm " + args);
}

}  // namespace pbm::test
