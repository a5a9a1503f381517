// resource_paths.h: the lookup order, the authority of $MOTIONSTYLE_RESOURCES, the build-tree rule,
// the install-prefix layout and shipped network names. Layouts are built in unique temp dirs.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "common/resource_paths.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

namespace fs = std::filesystem;

void makeResources(const fs::path& directory) {
  fs::create_directories(directory / "models");
  fs::create_directories(directory / "samples");
}

void touch(const fs::path& file) { std::ofstream(file) << "x"; }

class ResourcePathsTest : public ::testing::Test {
 protected:
  void SetUp() override { root_ = test::uniqueTempDir("resources"); }
  void TearDown() override {
    std::error_code error;
    fs::remove_all(root_, error);
  }
  fs::path root_;
};

// --- invalid input --------------------------------------------------------------------------

TEST_F(ResourcePathsTest, MissingOrPartialDirectoriesAreNotResources) {
  EXPECT_FALSE(isResourceDirectory(""));
  EXPECT_FALSE(isResourceDirectory(root_ / "absent"));
  fs::create_directories(root_ / "only_models" / "models");
  EXPECT_FALSE(isResourceDirectory(root_ / "only_models"));
  fs::create_directories(root_ / "files");
  touch(root_ / "files" / "models");  // a file, not a folder
  fs::create_directories(root_ / "files" / "samples");
  EXPECT_FALSE(isResourceDirectory(root_ / "files"));
}

TEST_F(ResourcePathsTest, NothingFoundWithoutAnyCandidate) {
  const ResourceSearch search;  // no override, executable unknown
  EXPECT_TRUE(resourceCandidates(search).empty());
  EXPECT_FALSE(findResourceDirectory(search).has_value());
  EXPECT_NE(describeResourceLookup(search).find("no resources directory"), std::string::npos);
}

TEST_F(ResourcePathsTest, AnInvalidOverrideIsNotSilentlyReplaced) {
  makeResources(root_ / "prefix" / "share" / "motionstyle");
  ResourceSearch search;
  search.executable = root_ / "prefix" / "bin" / "motionstyle-cli";
  ASSERT_TRUE(findResourceDirectory(search).has_value());
  search.override_directory = root_ / "typo";
  EXPECT_EQ(resourceCandidates(search), std::vector<fs::path>{root_ / "typo"});
  EXPECT_FALSE(findResourceDirectory(search).has_value());
  const std::string message = describeResourceLookup(search);
  EXPECT_NE(message.find((root_ / "typo").string()), std::string::npos) << message;
  EXPECT_NE(message.find("MOTIONSTYLE_RESOURCES"), std::string::npos) << message;
}

TEST_F(ResourcePathsTest, NetworkNamesCannotLeaveTheModelsFolder) {
  for (const char* bad : {"", "../elderly", "models/elderly", "/etc/passwd", "a b", "elderly.net", ".", ".."})
    EXPECT_FALSE(isValidNetworkName(bad)) << bad;
  EXPECT_FALSE(isValidNetworkName(std::string(129, 'a')));
  makeResources(root_ / "res");
  touch(root_ / "secret.net");
  EXPECT_FALSE(shippedNetworkFile(root_ / "res", "../secret").has_value());
  EXPECT_FALSE(shippedNetworkFile(root_ / "res", "absent").has_value());
  fs::create_directories(root_ / "res" / "models" / "folder.net");  // a folder is not a network
  EXPECT_FALSE(shippedNetworkFile(root_ / "res", "folder").has_value());
  EXPECT_TRUE(shippedNetworkFiles(root_ / "absent").empty());
}

// --- properties -----------------------------------------------------------------------------

TEST_F(ResourcePathsTest, AValidOverrideWinsOverEverythingElse) {
  makeResources(root_ / "override");
  makeResources(root_ / "source" / "resources");
  makeResources(root_ / "build" / "share" / "motionstyle");
  ResourceSearch search;
  search.override_directory = root_ / "override";
  search.executable = root_ / "build" / "bin" / "motionstyle-cli";
  search.build_tree = root_ / "build";
  search.source_resources = root_ / "source" / "resources";
  EXPECT_EQ(findResourceDirectory(search), root_ / "override");
  EXPECT_NE(describeResourceLookup(search).find((root_ / "override").string()), std::string::npos);
}

TEST_F(ResourcePathsTest, TheSourceTreeIsUsedOnlyFromInsideTheBuildTree) {
  makeResources(root_ / "source" / "resources");
  makeResources(root_ / "usr" / "share" / "motionstyle");
  ResourceSearch search;
  search.build_tree = root_ / "build";
  search.source_resources = root_ / "source" / "resources";

  search.executable = root_ / "build" / "app" / "cli" / "motionstyle-cli";
  EXPECT_EQ(findResourceDirectory(search), root_ / "source" / "resources");

  // The same binary installed: the source tree on this machine must not be read.
  search.executable = root_ / "usr" / "bin" / "motionstyle-cli";
  EXPECT_EQ(resourceCandidates(search).size(), 1u);
  EXPECT_EQ(findResourceDirectory(search), root_ / "usr" / "share" / "motionstyle");

  // A sibling whose name merely starts with the build dir's name is outside it.
  search.executable = root_ / "build-other" / "motionstyle-cli";
  EXPECT_EQ(resourceCandidates(search).size(), 1u);
}

TEST_F(ResourcePathsTest, TheInstallPrefixIsFoundBesideTheExecutablesFolder) {
  ResourceSearch search;
  search.executable = root_ / "opt" / "ms" / "bin" / "motionstyle";
  EXPECT_FALSE(findResourceDirectory(search).has_value());
  makeResources(root_ / "opt" / "ms" / "share" / "motionstyle");
  const auto found = findResourceDirectory(search);
  ASSERT_TRUE(found.has_value());
  EXPECT_TRUE(fs::equivalent(*found, root_ / "opt" / "ms" / "share" / "motionstyle"));
}

TEST_F(ResourcePathsTest, ShippedNetworksAreListedByNameInOrder) {
  makeResources(root_ / "res");
  for (const char* name : {"sad.net", "loss_network.net", "elderly.net", "NOTICE", "notes.txt", "bad name.net"})
    touch(root_ / "res" / "models" / name);
  const std::vector<fs::path> files = shippedNetworkFiles(root_ / "res");
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0].filename(), "elderly.net");
  EXPECT_EQ(files[1].filename(), "loss_network.net");
  EXPECT_EQ(files[2].filename(), "sad.net");
  EXPECT_EQ(shippedNetworkFile(root_ / "res", "elderly"), root_ / "res" / "models" / "elderly.net");
}

// This very test program runs from the build tree, so the real lookup must reach the source tree's
// resources/ (or the override, when one is set in the environment).
TEST(ResourceDirectoryTest, ThisBuildTreeFindsTheSourceResources) {
  const ResourceSearch search = currentResourceSearch();
  ASSERT_FALSE(search.executable.empty()) << "/proc/self/exe unreadable";
  if (search.override_directory) GTEST_SKIP() << "$MOTIONSTYLE_RESOURCES is set; the build-tree rule is not in play";
  const auto found = resourceDirectory();
  ASSERT_TRUE(found.has_value()) << describeResourceLookup(search);
  EXPECT_TRUE(fs::equivalent(*found, search.source_resources));
  EXPECT_TRUE(fs::exists(*found / "samples" / "cmu_131_01_walk.bvh"));
}

TEST(ResourceDirectoryTest, TheEnvironmentOverridesTheLookup) {
  const fs::path dir = test::uniqueTempDir("resources-env");
  makeResources(dir);
  ASSERT_EQ(::setenv(kResourcesEnvironmentVariable, dir.c_str(), 1), 0);
  const auto found = resourceDirectory();
  ASSERT_EQ(::setenv(kResourcesEnvironmentVariable, "", 1), 0);  // empty counts as unset
  EXPECT_EQ(found, dir);
  EXPECT_FALSE(currentResourceSearch().override_directory.has_value());
  ::unsetenv(kResourcesEnvironmentVariable);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace motionstyle
