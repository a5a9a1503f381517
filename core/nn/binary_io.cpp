#include "nn/binary_io.h"

#include <array>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "common/errors.h"
#include "common/text_safety.h"
#include "nn/half_float.h"

namespace motionstyle::nn {
namespace {

// Slicing-by-8 tables: tables[0] is the bytewise CRC table, tables[k][i] the CRC of byte i followed by k
// zero bytes, so eight bytes are folded in with eight lookups (a network file's 4 MB: 30 ms bytewise,
// a fifth of a one-clip stylize).
using CrcTables = std::array<std::array<std::uint32_t, 256>, 8>;

CrcTables makeCrcTables() {
  CrcTables tables{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1u) != 0 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    tables[0][i] = c;
  }
  for (std::size_t k = 1; k < 8; ++k)
    for (std::size_t i = 0; i < 256; ++i)
      tables[k][i] = (tables[k - 1][i] >> 8) ^ tables[0][tables[k - 1][i] & 0xFFu];
  return tables;
}

std::uint64_t loadLittleEndian(std::string_view bytes, int count) {
  std::uint64_t v = 0;
  for (int i = count - 1; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(bytes[static_cast<std::size_t>(i)]);
  return v;
}

}  // namespace

const char* weightPrecisionName(WeightPrecision precision) {
  return precision == WeightPrecision::F16 ? "f16" : "f32";
}

std::size_t bytesPerWeight(WeightPrecision precision) { return precision == WeightPrecision::F16 ? 2 : 4; }

std::uint32_t crc32(std::string_view bytes) {
  static const CrcTables tables = makeCrcTables();
  std::uint32_t c = 0xFFFFFFFFu;
  std::size_t i = 0;
  for (; i + 8 <= bytes.size(); i += 8) {
    const auto low = static_cast<std::uint32_t>(loadLittleEndian(bytes.substr(i, 4), 4)) ^ c;
    const auto high = static_cast<std::uint32_t>(loadLittleEndian(bytes.substr(i + 4, 4), 4));
    c = tables[7][low & 0xFFu] ^ tables[6][(low >> 8) & 0xFFu] ^ tables[5][(low >> 16) & 0xFFu] ^ tables[4][low >> 24] ^
        tables[3][high & 0xFFu] ^ tables[2][(high >> 8) & 0xFFu] ^ tables[1][(high >> 16) & 0xFFu] ^ tables[0][high >> 24];
  }
  for (; i < bytes.size(); ++i) c = tables[0][(c ^ static_cast<unsigned char>(bytes[i])) & 0xFFu] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

std::string contentHash(std::string_view bytes) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (char ch : bytes) {
    h ^= static_cast<unsigned char>(ch);
    h *= 0x100000001b3ull;
  }
  static const char* digits = "0123456789abcdef";
  std::string out = "fnv1a64:";
  for (int shift = 60; shift >= 0; shift -= 4) out.push_back(digits[(h >> shift) & 0xFu]);
  return out;
}

void ByteWriter::u32(std::uint32_t v) {
  for (int i = 0; i < 4; ++i) bytes_.push_back(static_cast<char>((v >> (8 * i)) & 0xFFu));
}

void ByteWriter::u64(std::uint64_t v) {
  for (int i = 0; i < 8; ++i) bytes_.push_back(static_cast<char>((v >> (8 * i)) & 0xFFu));
}

void ByteWriter::f64(double v) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  u64(bits);
}

void ByteWriter::str(std::string_view s) {
  const std::string safe = safeText(s);
  u32(static_cast<std::uint32_t>(safe.size()));
  bytes_.append(safe);
}

void ByteWriter::f64Vector(const Eigen::VectorXd& v) {
  u32(static_cast<std::uint32_t>(v.size()));
  for (Eigen::Index i = 0; i < v.size(); ++i) f64(v(i));
}

void ByteWriter::tensor(const std::string& name, const Mat<float>& m, WeightPrecision precision) {
  str(name);
  u32(static_cast<std::uint32_t>(m.rows()));
  u32(static_cast<std::uint32_t>(m.cols()));
  if (precision == WeightPrecision::F16) {
    for (Eigen::Index i = 0; i < m.size(); ++i) {
      const std::uint16_t half = floatToHalf(m.data()[i]);
      if ((half & 0x7C00u) == 0x7C00u)  // infinity or NaN
        throw std::invalid_argument("tensor '" + name + "': value " + std::to_string(m.data()[i]) +
                                    " cannot be stored as f16 (finite range +-65504); store this network as f32");
      bytes_.push_back(static_cast<char>(half & 0xFFu));
      bytes_.push_back(static_cast<char>(half >> 8));
    }
    return;
  }
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, m.data() + i, sizeof bits);
    u32(bits);
  }
}

void ByteReader::fail(const std::string& detail) const { throw InputError(file_, 0, detail); }

void ByteReader::need(std::size_t count, const char* what) const {
  if (count > remaining())
    fail(std::string("truncated or corrupt network file: ") + what + " needs " + std::to_string(count) +
         " bytes at offset " + std::to_string(position_) + ", only " + std::to_string(remaining()) + " left");
}

std::string_view ByteReader::take(std::size_t count, const char* what) {
  need(count, what);
  const std::string_view out = bytes_.substr(position_, count);
  position_ += count;
  return out;
}

std::uint8_t ByteReader::u8(const char* what) { return static_cast<std::uint8_t>(take(1, what)[0]); }

std::uint32_t ByteReader::u32(const char* what) {
  return static_cast<std::uint32_t>(loadLittleEndian(take(4, what), 4));
}

std::uint64_t ByteReader::u64(const char* what) { return loadLittleEndian(take(8, what), 8); }

double ByteReader::f64(const char* what) {
  const std::uint64_t bits = u64(what);
  double v = 0;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

std::string ByteReader::str(const char* what, std::uint32_t max_length) {
  const std::uint32_t length = u32(what);
  if (length > max_length)
    fail(std::string("corrupt network file: ") + what + " claims " + std::to_string(length) + " bytes");
  std::string text(take(length, what));
  if (const std::string problem = textSafetyProblem(text); !problem.empty())
    fail(std::string("corrupt network file: ") + what + " is not safe text (" + problem + ")");
  return text;
}

Eigen::VectorXd ByteReader::f64Vector(const char* what) {
  const std::uint32_t count = u32(what);
  need(static_cast<std::size_t>(count) * 8, what);  // before allocating
  Eigen::VectorXd v(count);
  for (std::uint32_t i = 0; i < count; ++i) v(i) = f64(what);
  return v;
}

ByteReader::Tensor ByteReader::tensor(WeightPrecision precision) {
  Tensor t;
  t.name = str("tensor name", 256);
  const std::uint32_t rows = u32("tensor rows");
  const std::uint32_t cols = u32("tensor cols");
  const std::uint64_t count = static_cast<std::uint64_t>(rows) * cols;
  const std::uint64_t size = count * bytesPerWeight(precision);  // 64-bit: no overflow for 32-bit rows and cols
  if (size > remaining())
    fail("truncated or corrupt network file: tensor '" + t.name + "' of " + std::to_string(rows) + " x " +
         std::to_string(cols) + " needs " + std::to_string(size) + " bytes, only " +
         std::to_string(remaining()) + " left");
  t.value.resize(rows, cols);
  const std::string_view data = take(static_cast<std::size_t>(size), "tensor data");
  if (precision == WeightPrecision::F16) {
    for (std::uint64_t i = 0; i < count; ++i)
      t.value.data()[i] = halfToFloat(static_cast<std::uint16_t>(loadLittleEndian(data.substr(static_cast<std::size_t>(i) * 2, 2), 2)));
    return t;
  }
  for (std::uint64_t i = 0; i < count; ++i) {
    const auto bits = static_cast<std::uint32_t>(loadLittleEndian(data.substr(static_cast<std::size_t>(i) * 4, 4), 4));
    std::memcpy(t.value.data() + i, &bits, sizeof bits);
  }
  return t;
}

std::string readFileBytes(const std::filesystem::path& file, std::uintmax_t max_bytes, const std::string& what) {
  std::error_code error;
  if (std::filesystem::exists(file, error) && !std::filesystem::is_regular_file(file, error))
    throw InputError(file.string(), 0, "not a " + what + " (not a regular file)");
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  if (error) throw InputError(file.string(), 0, "cannot read " + what + ": " + error.message());
  if (size > max_bytes) throw InputError(file.string(), 0, "not a " + what + ": " + std::to_string(size) + " bytes is too large");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), 0, "cannot open " + what);
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  if (static_cast<std::uintmax_t>(in.gcount()) != size) throw InputError(file.string(), 0, "cannot read " + what);
  return bytes;
}

}  // namespace motionstyle::nn
