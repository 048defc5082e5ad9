// atomic_output_file_test.cpp - temp-then-rename output files and the early output-directory check.
#include "cli/atomic_output_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "common/error.h"
#include "temp_directory.h"

namespace ht::cli {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::StartsWith;

std::string contents(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(CliAtomicOutputFile, CommitMovesTheTemporaryFileIntoPlace) {
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

TEST(CliAtomicOutputFile, WithoutCommitNothingIsLeftAndOldFileSurvives) {
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

TEST(CliAtomicOutputFile, PrepareOutputDirectoryCreatesParentsOrNamesTheProblem) {
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

}  // namespace
}  // namespace ht::cli
