// StagedDirectory: the files are written beside the directory and appear in
// it only on commit, all at once; an abandoned or failed stage leaves
// nothing behind.
#include "support/atomic_directory.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "support/file_io.h"

namespace spire {
namespace {

namespace fs = std::filesystem;

class StagedDirectoryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::path(::testing::TempDir()) /
            ("staged_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
             std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  // Every entry under the root, by relative path.
  std::set<std::string> entries() const {
    std::set<std::string> names;
    for (const auto& entry : fs::recursive_directory_iterator(root_)) names.insert(fs::relative(entry, root_).string());
    return names;
  }
  std::string dir() const { return (root_ / "out" / "Shader").string(); }

  fs::path root_;
};

TEST_F(StagedDirectoryTest, FilesAppearOnlyOnCommitAndReplaceTheOldSet) {
  ASSERT_TRUE(replaceDirectoryAtomically(dir(), {{"old.txt", "old"}, {"both.txt", "1"}}));
  auto staged = StagedDirectory::stage(dir(), {{"both.txt", "2"}, {"new.txt", "new"}});
  ASSERT_TRUE(staged) << staged.error().message;
  EXPECT_EQ(readWholeFile(dir() + "/both.txt"), "1");
  EXPECT_FALSE(fs::exists(dir() + "/new.txt"));
  ASSERT_TRUE(staged.value().commit());
  EXPECT_EQ(entries(), (std::set<std::string>{"out", "out/Shader", "out/Shader/both.txt", "out/Shader/new.txt"}));
  EXPECT_EQ(readWholeFile(dir() + "/both.txt"), "2");
}

TEST_F(StagedDirectoryTest, AStageThatIsNeverCommittedLeavesNothing) {
  {
    auto staged = StagedDirectory::stage(dir(), {{"a.txt", "a"}});
    ASSERT_TRUE(staged);
    auto moved = std::move(staged).value();
    EXPECT_EQ(entries().size(), 3u);  // out/, the staging folder and its file
  }
  EXPECT_EQ(entries(), (std::set<std::string>{"out"}));
}

TEST_F(StagedDirectoryTest, CommitDecidesWhetherTheDirectoryExistsWhenItRuns) {
  auto first = StagedDirectory::stage(dir(), {{"a.txt", "first"}});
  auto second = StagedDirectory::stage(dir(), {{"a.txt", "second"}});
  ASSERT_TRUE(first && second);
  ASSERT_TRUE(first.value().commit());   // creates the directory
  ASSERT_TRUE(second.value().commit());  // replaces it
  EXPECT_EQ(readWholeFile(dir() + "/a.txt"), "second");
  EXPECT_EQ(entries(), (std::set<std::string>{"out", "out/Shader", "out/Shader/a.txt"}));
}

TEST_F(StagedDirectoryTest, APathThatBecameAFileFailsTheCommitAndRemovesTheStage) {
  auto staged = StagedDirectory::stage(dir(), {{"a.txt", "a"}});
  ASSERT_TRUE(staged);
  std::ofstream(dir()) << "not a folder";
  const auto committed = staged.value().commit();
  ASSERT_FALSE(committed);
  EXPECT_NE(committed.error().message.find("exists and is not a directory"), std::string::npos);
  EXPECT_EQ(entries(), (std::set<std::string>{"out", "out/Shader"}));
  EXPECT_EQ(readWholeFile(dir()), "not a folder");
}

TEST(WriteNewFile, RefusesToReplaceAFile) {
  const std::string path =
      (fs::path(::testing::TempDir()) / ("write_new_" + std::to_string(::getpid()) + ".txt")).string();
  fs::remove(path);
  ASSERT_TRUE(writeNewFile(path, "one"));
  const auto again = writeNewFile(path, "two");
  ASSERT_FALSE(again);
  EXPECT_NE(again.error().message.find(path), std::string::npos);
  EXPECT_EQ(readWholeFile(path), "one");
  fs::remove(path);
}

}  // namespace
}  // namespace spire
