// FileReplacement (io_surfel/file_replacement.h): a save never destroys what was there, never
// writes through a link or a file planted beside the target, and writes devices in place.
#include "part_files.h"

#include <file_replacement.h>

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

namespace {

using surfel_io::FileReplacement;

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A new, empty folder for one test (a rerun gets another).
std::string folderFor(const std::string& test) {
  std::string name = testing::TempDir() + "file_replacement_" + test + "_XXXXXX";
  if (::mkdtemp(&name[0]) == nullptr) ADD_FAILURE() << "cannot make a folder like " << name;
  return name + "/";
}

TEST(FileReplacement, ReplacesTheTargetOnlyOnCommitAndKeepsItsPermissions) {
  const std::string path = folderFor("commit") + "out.surfel";
  std::ofstream(path) << "previous";
  ASSERT_EQ(::chmod(path.c_str(), 0640), 0);
  std::string error;
  {
    FileReplacement replacement;
    ASSERT_TRUE(replacement.open(path, error)) << error;
    EXPECT_NE(replacement.writePath(), path);
    EXPECT_EQ(partFilesBeside(path), 1);
    std::ofstream(replacement.writePath()) << "new";
    EXPECT_EQ(contents(path), "previous");
    ASSERT_TRUE(replacement.commit(error)) << error;
  }
  EXPECT_EQ(contents(path), "new");
  struct stat st;
  ASSERT_EQ(::stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0640u);
  EXPECT_EQ(partFilesBeside(path), 0);
}

TEST(FileReplacement, AnAbandonedSaveLeavesTheTargetAndNoTemporaryFile) {
  const std::string path = folderFor("abandon") + "out.ply";
  std::ofstream(path) << "previous";
  std::string error;
  {
    FileReplacement replacement;
    ASSERT_TRUE(replacement.open(path, error)) << error;
    std::ofstream(replacement.writePath()) << "half";
  }
  EXPECT_EQ(contents(path), "previous");
  EXPECT_EQ(partFilesBeside(path), 0);
}

// Two saves of one path at once (a retried task beside its first run) get files of their own.
TEST(FileReplacement, ConcurrentSavesWriteFilesOfTheirOwn) {
  const std::string path = folderFor("concurrent") + "out.ply";
  std::string error;
  FileReplacement first, second;
  ASSERT_TRUE(first.open(path, error)) << error;
  ASSERT_TRUE(second.open(path, error)) << error;
  EXPECT_NE(first.writePath(), second.writePath());
  EXPECT_EQ(partFilesBeside(path), 2);
}

// What sits at the old fixed temporary name, or any other file, is never written through.
TEST(FileReplacement, ALinkBesideTheTargetIsNotFollowed) {
  const std::string folder = folderFor("planted");
  const std::string victim = folder + "victim.txt", path = folder + "out.surfel";
  std::ofstream(victim) << "precious";
  ASSERT_EQ(::symlink(victim.c_str(), (path + ".part").c_str()), 0);
  std::string error;
  FileReplacement replacement;
  ASSERT_TRUE(replacement.open(path, error)) << error;
  std::ofstream(replacement.writePath()) << "surfels";
  ASSERT_TRUE(replacement.commit(error)) << error;
  EXPECT_EQ(contents(victim), "precious");
  EXPECT_EQ(contents(path), "surfels");
}

// A link at the target itself names the file to replace: that file changes, the link stays.
TEST(FileReplacement, ALinkAtTheTargetReplacesTheFileItNames) {
  const std::string folder = folderFor("link");
  const std::string named = folder + "named.ply", link = folder + "link.ply";
  std::ofstream(named) << "previous";
  ASSERT_EQ(::symlink(named.c_str(), link.c_str()), 0);
  std::string error;
  FileReplacement replacement;
  ASSERT_TRUE(replacement.open(link, error)) << error;
  std::ofstream(replacement.writePath()) << "new";
  ASSERT_TRUE(replacement.commit(error)) << error;
  struct stat st;
  ASSERT_EQ(::lstat(link.c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode));
  EXPECT_EQ(contents(named), "new");
}

TEST(FileReplacement, ADeviceIsWrittenInPlace) {
  std::string error;
  FileReplacement replacement;
  ASSERT_TRUE(replacement.open("/dev/null", error)) << error;
  EXPECT_EQ(replacement.writePath(), "/dev/null");
  std::ofstream("/dev/null") << "discarded";
  ASSERT_TRUE(replacement.commit(error)) << error;
  struct stat st;
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
}

TEST(FileReplacement, UnwritablePathsFailAtOpenWithTheReason) {
  const std::string folder = folderFor("unwritable");
  std::string error;
  FileReplacement replacement;
  EXPECT_FALSE(replacement.open(folder, error));
  EXPECT_NE(error.find("it is a folder"), std::string::npos) << error;
  EXPECT_FALSE(replacement.open("", error));
  EXPECT_NE(error.find("the path is empty"), std::string::npos) << error;
  EXPECT_FALSE(replacement.open(folder + "missing/out.ply", error));
  EXPECT_NE(error.find("cannot write '" + folder + "missing/out.ply': No such file or directory"), std::string::npos)
      << error;
  // A name at the longest a file name may be still gets a temporary name that fits.
  const std::string longest = folder + std::string(255, 'n');
  EXPECT_TRUE(replacement.open(longest, error)) << error;
}

}  // namespace
