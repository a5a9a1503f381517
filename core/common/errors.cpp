#include "common/errors.h"

namespace motionstyle {
namespace {

std::string formatInputError(const std::string& file, int line, const std::string& detail) {
  std::string where = file.empty() ? std::string("<input>") : file;
  if (line > 0) where.append(":").append(std::to_string(line));
  return where.append(": ").append(detail);
}

}  // namespace

InputError::InputError(std::string file, int line, std::string detail)
    : Error(formatInputError(file, line, detail)),
      file_(std::move(file)),
      line_(line),
      detail_(std::move(detail)) {}

WriteError::WriteError(std::string file, std::string detail)
    : Error(std::string(file).append(": cannot write: ").append(detail)), file_(std::move(file)) {}

}  // namespace motionstyle
