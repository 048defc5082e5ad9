// atomic_output_file_test.cpp - temp-then-rename output files, file sets that appear whole or not at all, and the
// early output-directory check.
#include "frame_io/atomic_output_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "common/error.h"
#include "tests/common/temp_directory.h"

namespace ht::frame_io {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::StartsWith;

std::string contents(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(AtomicOutputFile, CommitMovesTheTemporaryFileIntoPlace) {
  test::TempDirectory dir;
  const fs::path target = dir.path() / "result.txt";
  {
    AtomicOutputFile file(target);
    EXPECT_EQ(file.tempPath().parent_path(), dir.path());
    EXPECT_THAT(file.tempPath().filename().string(), StartsWith(".result.txt.tmp-"));
    std::ofstream(file.tempPath()) << "complete";
    EXPECT_FALSE(fs::exists(target)) << "the target must not appear before commit()";
    file.commit();
  }
  EXPECT_EQ(contents(target), "complete");
  EXPECT_THAT(dir.entries(), ElementsAre("result.txt"));
}

TEST(AtomicOutputFile, WithoutCommitNothingIsLeftAndOldFileSurvives) {
  test::TempDirectory dir;
  const fs::path target = dir.path() / "result.txt";
  std::ofstream(target) << "previous";
  {
    AtomicOutputFile file(target);
    std::ofstream(file.tempPath()) << "half writ";
  }  // e.g. an exception while writing
  EXPECT_EQ(contents(target), "previous");
  EXPECT_THAT(dir.entries(), ElementsAre("result.txt"));
}

TEST(AtomicOutputFile, PrepareOutputDirectoryCreatesParentsOrNamesTheProblem) {
  test::TempDirectory dir;
  prepareOutputDirectory(dir.path() / "x" / "y" / "frame.png");
  EXPECT_TRUE(fs::is_directory(dir.path() / "x" / "y"));
  EXPECT_THAT(dir.entries(), ElementsAre("x"));

  std::ofstream(dir.path() / "file") << "not a directory";
  try {
    prepareOutputDirectory(dir.path() / "file" / "frame.png");
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr((dir.path() / "file" / "frame.png").string()));
    EXPECT_THAT(e.what(), HasSubstr("Not a directory"));
  }
  EXPECT_THROW(AtomicOutputFile(dir.path() / "file" / "frame.png"), IoError);
  EXPECT_THROW(AtomicOutputFile(""), IoError);
}

std::vector<std::uint8_t> bytesOf(const std::string& text) { return {text.begin(), text.end()}; }

TEST(AtomicOutputFile, FileSetAppearsWholeWithNoTemporaryLeft) {
  test::TempDirectory dir;
  const std::vector<OutputFile> files = {{dir.path() / "q.png", bytesOf("quilt")},
                                         {dir.path() / "q.json", bytesOf("{}")},
                                         {dir.path() / "exr" / "q.exr", bytesOf("views")}};
  writeFilesAtomically(files);
  EXPECT_THAT(dir.entries(), ElementsAre("exr", "q.json", "q.png"));
  EXPECT_EQ(contents(dir.path() / "q.png"), "quilt");
  EXPECT_EQ(contents(dir.path() / "exr" / "q.exr"), "views");
}

TEST(AtomicOutputFile, FileSetWithOneUnwritableFileWritesNoneOfThem) {
  test::TempDirectory dir;
  std::ofstream(dir.path() / "q.png") << "previous";
  std::ofstream(dir.path() / "blocker") << "a file where a directory is needed";
  const std::vector<OutputFile> files = {{dir.path() / "q.png", bytesOf("quilt")},
                                         {dir.path() / "q.json", bytesOf("{}")},
                                         {dir.path() / "blocker" / "q.exr", bytesOf("views")}};
  EXPECT_THROW(writeFilesAtomically(files), IoError);
  EXPECT_THAT(dir.entries(), ElementsAre("blocker", "q.png"));
  EXPECT_EQ(contents(dir.path() / "q.png"), "previous");
}

}  // namespace
}  // namespace ht::frame_io
