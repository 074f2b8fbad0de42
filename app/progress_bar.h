// A one-line progress bar on stderr for long CLI runs; silent when stderr is not a terminal, so
// logs and CI output stay clean.
#pragma once

#include <chrono>
#include <string>

namespace pbm {

class ProgressBar {
 public:
  ProgressBar(std::string label, long total);
  void update(long done, const std::string& detail = {});
  void finish();

 private:
  std::string label_;
  long total_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace pbm
