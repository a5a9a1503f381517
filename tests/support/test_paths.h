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
// fixed names under /tmp would race. The caller removes it (ScopedTempDir does).
inline std::filesystem::path uniqueTempDir(const std::string& purpose) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::random_device entropy;
  const std::string name = "motionstyle-" + purpose + "-" + (info ? std::string(info->name()) : std::string("test")) +
                           "-" + std::to_string(::getpid()) + "-" + std::to_string(entropy());
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / name;
  std::filesystem::create_directories(dir);
  return dir;
}

// uniqueTempDir removed with its contents when the test's scope ends.
class ScopedTempDir {
 public:
  explicit ScopedTempDir(const std::string& purpose) : path_(uniqueTempDir(purpose)) {}
  ~ScopedTempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScopedTempDir(const ScopedTempDir&) = delete;
  ScopedTempDir& operator=(const ScopedTempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

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
