#pragma once
// The failures the core reports on purpose, under one base (f3d's exception hierarchy is the model).
// Each front end translates them once: the CLI to an exit code and a line on stderr (app/cli/main.cpp),
// the app to a message for the user (app/gui/error_text.h).
//
//   Error               the base: what() is a complete sentence for the user.
//   InputError          the user's data is wrong (a malformed BVH, an unmappable rig, a corrupt network
//                       file); names the file and, where it applies, the 1-based line.  CLI exit 2.
//   WriteError          an output cannot be written (disk full, permission, a folder); the destination
//                       is left untouched.                                                CLI exit 2.
//   TrainingDiverged    a loss or weight became NaN or infinite; the last good checkpoint is kept. exit 1.
//   OperationCancelled  the caller's cancel flag was seen (not a failure: no message is shown). exit 130.
// Anything else thrown from core (std::invalid_argument for a bad setting, std::bad_alloc, ...) is a
// programming or resource error: exit 1, "internal error" in the app.

#include <stdexcept>
#include <string>

namespace motionstyle {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class InputError : public Error {
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

class WriteError : public Error {
 public:
  WriteError(std::string file, std::string detail);
  const std::string& file() const noexcept { return file_; }

 private:
  std::string file_;
};

class TrainingDiverged : public Error {
 public:
  using Error::Error;
};

class OperationCancelled : public Error {
 public:
  OperationCancelled() : Error("operation cancelled") {}
};

}  // namespace motionstyle
