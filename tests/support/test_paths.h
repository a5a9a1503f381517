#pragma once
// Paths to test data. Committed fixtures are always present; the licensed dataset may not be.

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <random>
#include <string>

namespace motionstyle::test {

inline std::filesystem::path fixture(const std::string& name) {
  return std::filesystem::path(MOTIONSTYLE_TEST_DATA_DIR) / name;
}

// ../shared/data/bandai, or an empty path when the dataset is not beside the project.
inline std::filesystem::path bandaiDir() {
  const std::filesystem::path dir = std::filesystem::path(MOTIONSTYLE_SHARED_DATA_DIR) / "bandai";
  return std::filesystem::is_directory(dir) ? dir : std::filesystem::path();
}

// A new, empty directory for one test, unique across processes: ctest runs tests in parallel, so
// fixed names under /tmp would race. The caller removes it (TempDir does).
inline std::filesystem::path uniqueTempDir(const std::string& purpose) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::random_device entropy;
  const std::string name = "motionstyle-" + purpose + "-" + (info ? std::string(info->name()) : std::string("test")) +
                           "-" + std::to_string(::getpid()) + "-" + std::to_string(entropy());
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / name;
  std::filesystem::create_directories(dir);
  return dir;
}

// A uniqueTempDir removed with its contents when the object goes away.
class TempDir {
 public:
  explicit TempDir(const std::string& purpose = "test") : path_(uniqueTempDir(purpose)) {}
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace motionstyle::test

// Use at the top of a test that needs the licensed dataset (label "data").
#define MOTIONSTYLE_REQUIRE_BANDAI(dir_var)                                                         \
  const std::filesystem::path dir_var = ::motionstyle::test::bandaiDir();                           \
  if (dir_var.empty())                                                                              \
    GTEST_SKIP() << "../shared/data/bandai is absent: skipping a test that needs the licensed dataset " \
                    "(set MOTIONSTYLE_SHARED_DATA_DIR to run it)"
