// writeFileAtomically and AtomicFileBatch: failures leave every destination as it was and no
// temporary behind; what the user owns (permissions, symlinks) is kept; stale temporaries of dead
// processes are removed, those of live processes are not.
#include "common/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/errors.h"

namespace motionstyle {
namespace {

namespace fs = std::filesystem;

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("motionstyle-atomic-" + std::to_string(::getpid()) + "-" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  static std::string read(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  static void write(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }
  // Names in the folder other than `keep`.
  int entriesBesides(std::initializer_list<std::string> keep) const {
    int count = 0;
    for (const auto& entry : fs::directory_iterator(folder_)) {
      bool kept = false;
      for (const std::string& name : keep) kept = kept || entry.path().filename() == name;
      if (!kept) ++count;
    }
    return count;
  }
  static pid_t deadProcessId() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    int status = 0;
    ::waitpid(child, &status, 0);
    return child;
  }

  fs::path folder_;
};

// ---- invalid destinations and failing writers first --------------------------------------------

TEST_F(AtomicFileTest, RefusesAFolderAndAMissingFolder) {
  fs::create_directories(folder_ / "sub");
  EXPECT_THROW(writeFileAtomically(folder_ / "sub", "x"), WriteError);
  EXPECT_TRUE(fs::is_directory(folder_ / "sub"));
  EXPECT_THROW(writeFileAtomically(folder_ / "missing" / "out.bvh", "x"), WriteError);
  EXPECT_EQ(entriesBesides({"sub"}), 0);
}

TEST_F(AtomicFileTest, AThrowingWriterLeavesTheOldFileAndNoTemporary) {
  write(folder_ / "out.bvh", "old");
  EXPECT_THROW(writeFileAtomically(folder_ / "out.bvh", [](std::ostream& out) {
                 out << "half";
                 throw std::runtime_error("boom");
               }),
               std::runtime_error);
  EXPECT_EQ(read(folder_ / "out.bvh"), "old");
  EXPECT_EQ(entriesBesides({"out.bvh"}), 0);
}

TEST_F(AtomicFileTest, ABatchThatFailsWhileStagingWritesNothing) {
  write(folder_ / "clip.bvh", "old clip");
  {
    AtomicFileBatch batch;
    batch.stage(folder_ / "clip.bvh", "new clip");
    EXPECT_THROW(batch.stage(folder_ / "missing" / "metrics.json", "{}"), WriteError);
  }  // destroyed without commit
  EXPECT_EQ(read(folder_ / "clip.bvh"), "old clip");
  EXPECT_EQ(entriesBesides({"clip.bvh"}), 0);
}

// ---- properties ---------------------------------------------------------------------------------

TEST_F(AtomicFileTest, ABatchWritesEveryFileOnCommit) {
  AtomicFileBatch batch;
  batch.stage(folder_ / "clip.bvh", "clip");
  batch.stage(folder_ / "metrics.json", "{}");
  EXPECT_FALSE(fs::exists(folder_ / "clip.bvh"));  // nothing visible before the commit
  batch.commit();
  EXPECT_EQ(read(folder_ / "clip.bvh"), "clip");
  EXPECT_EQ(read(folder_ / "metrics.json"), "{}");
  EXPECT_EQ(entriesBesides({"clip.bvh", "metrics.json"}), 0);
}

// Unsynced skips only the fsync: the old file is replaced whole, its permissions kept, no temporary left.
TEST_F(AtomicFileTest, AnUnsyncedWriteIsStillAWholeSwap) {
  write(folder_ / "run.checkpoint", "old");
  fs::permissions(folder_ / "run.checkpoint", fs::perms::owner_read | fs::perms::owner_write);
  writeFileAtomically(folder_ / "run.checkpoint", "new", FileDurability::Unsynced);
  EXPECT_EQ(read(folder_ / "run.checkpoint"), "new");
  EXPECT_EQ(fs::status(folder_ / "run.checkpoint").permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_EQ(entriesBesides({"run.checkpoint"}), 0);
}

TEST_F(AtomicFileTest, KeepsTheExistingFilesPermissions) {
  write(folder_ / "private.bvh", "old");
  fs::permissions(folder_ / "private.bvh", fs::perms::owner_read | fs::perms::owner_write);
  writeFileAtomically(folder_ / "private.bvh", "new");
  EXPECT_EQ(read(folder_ / "private.bvh"), "new");
  EXPECT_EQ(fs::status(folder_ / "private.bvh").permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write);
}

TEST_F(AtomicFileTest, WritesThroughASymlinkChainToItsTarget) {
  fs::create_directories(folder_ / "store");
  write(folder_ / "store" / "take.bvh", "old");
  fs::create_symlink("store/take.bvh", folder_ / "middle.bvh");  // relative links, two hops
  fs::create_symlink("middle.bvh", folder_ / "link.bvh");
  writeFileAtomically(folder_ / "link.bvh", "new");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(folder_ / "link.bvh")));
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(folder_ / "middle.bvh")));
  EXPECT_EQ(read(folder_ / "store" / "take.bvh"), "new");
  EXPECT_EQ(entriesBesides({"store", "middle.bvh", "link.bvh"}), 0);
}

TEST_F(AtomicFileTest, RemovesStaleTemporariesOfDeadProcessesOnly) {
  const std::string dead = ".out.bvh.tmp-" + std::to_string(deadProcessId()) + "-1a2b";
  const std::string alive = ".out.bvh.tmp-" + std::to_string(::getppid()) + "-3c4d";
  const std::string other_file = ".other.bvh.tmp-" + std::to_string(deadProcessId()) + "-5e6f";
  const std::string not_ours = ".out.bvh.tmp-notapid";
  for (const std::string& name : {dead, alive, other_file, not_ours}) write(folder_ / name, "stale");
  writeFileAtomically(folder_ / "out.bvh", "new");
  EXPECT_FALSE(fs::exists(folder_ / dead));
  EXPECT_TRUE(fs::exists(folder_ / alive));       // its writer may still be running
  EXPECT_TRUE(fs::exists(folder_ / other_file));  // another destination's: not this write's business
  EXPECT_TRUE(fs::exists(folder_ / not_ours));
  EXPECT_EQ(read(folder_ / "out.bvh"), "new");
}

TEST_F(AtomicFileTest, TemporariesNameTheirProcess) {
  std::string seen;
  writeFileAtomically(folder_ / "out.bvh", [&](std::ostream& out) {
    for (const auto& entry : fs::directory_iterator(folder_)) seen = entry.path().filename().string();
    out << "x";
  });
  EXPECT_EQ(seen.rfind(".out.bvh.tmp-" + std::to_string(::getpid()) + "-", 0), 0u) << seen;
}

}  // namespace
}  // namespace motionstyle
