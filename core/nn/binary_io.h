#pragma once
// Little-endian binary encoding for the network file (NETWORK_FORMAT.md): a writer that appends to a
// byte string and a reader that checks EVERY length against the bytes that remain before it reads or
// allocates, throwing InputError (file name, line 0) instead. Plus CRC-32 and an FNV-1a content hash.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "nn/tensor.h"

namespace motionstyle::nn {

// How a network file stores its weights (NETWORK_FORMAT.md, "weight encoding"; format 2 on). The
// values are the file's codes. Weights are always float32 in memory.
enum class WeightPrecision : std::uint32_t {
  F32 = 1,  // IEEE binary32, exact
  F16 = 2,  // IEEE binary16 (nn/half_float.h), half the size, relative rounding error <= 2^-11
};
const char* weightPrecisionName(WeightPrecision precision);  // "f32", "f16"
std::size_t bytesPerWeight(WeightPrecision precision);       // 4, 2

// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320, init and final xor 0xFFFFFFFF), the zlib one.
std::uint32_t crc32(std::string_view bytes);

// FNV-1a 64-bit of the bytes as "fnv1a64:" + 16 lowercase hex digits: identifies a style clip's file.
std::string contentHash(std::string_view bytes);

// The whole of `file`, refused before a byte is read when it is not a regular file (a device, a
// folder) or holds more than max_bytes: InputError naming the file and `what` ("network file").
std::string readFileBytes(const std::filesystem::path& file, std::uintmax_t max_bytes, const std::string& what);

class ByteWriter {
 public:
  void u8(std::uint8_t v) { bytes_.push_back(static_cast<char>(v)); }
  void u32(std::uint32_t v);
  void u64(std::uint64_t v);
  void f64(double v);
  void str(std::string_view s);                 // u32 length + the bytes of safeText(s)
  void f64Vector(const Eigen::VectorXd& v);     // u32 count + f64 values
  // str name, u32 rows, u32 cols, then the values column-major in `precision`. F16 throws
  // std::invalid_argument naming the tensor for a value that is not finite in binary16 (|w| >= 65520,
  // NaN, infinity): a file that could not be read back is never written.
  void tensor(const std::string& name, const Mat<float>& m, WeightPrecision precision = WeightPrecision::F32);
  void raw(std::string_view s) { bytes_.append(s); }
  const std::string& bytes() const { return bytes_; }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

class ByteReader {
 public:
  // `file` names the source in error messages.
  ByteReader(std::string_view bytes, std::string file) : bytes_(bytes), file_(std::move(file)) {}

  std::uint8_t u8(const char* what);
  std::uint32_t u32(const char* what);
  std::uint64_t u64(const char* what);
  double f64(const char* what);
  // Strings longer than max_length, or not safe text (valid UTF-8 without control characters,
  // common/text_safety.h), are rejected as corrupt; the message names the offending byte, never echoes it.
  std::string str(const char* what, std::uint32_t max_length = 1u << 20);
  Eigen::VectorXd f64Vector(const char* what);
  struct Tensor {
    std::string name;
    Mat<float> value;
  };
  Tensor tensor(WeightPrecision precision = WeightPrecision::F32);
  std::string_view take(std::size_t count, const char* what);

  std::size_t remaining() const { return bytes_.size() - position_; }
  std::size_t position() const { return position_; }
  const std::string& file() const { return file_; }
  [[noreturn]] void fail(const std::string& detail) const;

 private:
  void need(std::size_t count, const char* what) const;

  std::string_view bytes_;
  std::string file_;
  std::size_t position_ = 0;
};

}  // namespace motionstyle::nn
