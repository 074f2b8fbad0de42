// pbm::Error: bad input at a boundary, carrying the file and the JSON path of the field
// (docs/architecture.md, "Errors and exit codes"). Numerical failures mid-step are not
// exceptions: the stability guard of advance_frame (sim/world.h) handles them
// (docs/architecture.md, "Stability guard").
#pragma once

#include <stdexcept>
#include <string>

namespace pbm {

class Error : public std::runtime_error {
 public:
  Error(std::string file, std::string path, const std::string& message)
      : std::runtime_error(compose(file, path, message)),
        file_(std::move(file)),
        path_(std::move(path)) {}
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }

 private:
  static std::string compose(const std::string& file, const std::string& path,
                             const std::string& message) {
    std::string s = file.empty() ? std::string() : file + ": ";
    if (!path.empty()) s += path + ": ";
    return s + message;
  }
  std::string file_;
  std::string path_;
};

}  // namespace pbm
