#pragma once
// Error types shared by every core module.
//
// InputError: the user's data is wrong (a malformed BVH, an unmappable rig, a corrupt network file).
//   It names the file and, where it applies, the 1-based line, plus what was expected. The CLI maps it to
//   exit code 2; the GUI shows it in a dialog.
// Anything else thrown from core (std::runtime_error, std::bad_alloc, ...) is an internal error: exit 1.

#include <stdexcept>
#include <string>

namespace motionstyle {

class InputError : public std::runtime_error {
 public:
  // line == 0 means "the file as a whole" (no line applies, e.g. a binary network file).
  InputError(std::string file, int line, std::string detail);

  const std::string& file() const noexcept { return file_; }
  int line() const noexcept { return line_; }
  const std::string& detail() const noexcept { return detail_; }

 private:
  std::string file_;
  int line_;
  std::string detail_;
};

// An I/O failure while writing (disk full, permission denied). The destination is left untouched.
class WriteError : public std::runtime_error {
 public:
  WriteError(std::string file, std::string detail);
  const std::string& file() const noexcept { return file_; }

 private:
  std::string file_;
};

}  // namespace motionstyle
