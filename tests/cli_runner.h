// Runs the built `pbm` with arguments and collects its exit code and output (stdout + stderr).
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace pbm::test {

struct CliResult {
  int code = -1;
  std::string output;
};

inline CliResult run_pbm(const std::string& args) {
  const std::string cmd = std::string(PBM_BINARY_DIR) + "/app/pbm " + args + " 2>&1";
  CliResult r;
  FILE* pipe = popen(cmd.c_str(), "r");
  char buf[4096];
  while (std::fgets(buf, sizeof buf, pipe)) r.output += buf;
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace pbm::test
