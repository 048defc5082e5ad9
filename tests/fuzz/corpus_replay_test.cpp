// corpus_replay_test.cpp - runs every file of one fuzz target's seed corpus (HT_FUZZ_CORPUS_DIR) through its
// LLVMFuzzerTestOneInput in the normal GCC builds, so the ASan suite re-checks seeds and saved crash reproducers.
// A finding aborts the process (as under libFuzzer); an unexpected exception type fails the test here.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

std::vector<std::uint8_t> readBytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// HT_FUZZ_SUITE (e.g. FuzzCorpusQuiltName) keeps the ctest names of the three replay programs apart.
TEST(HT_FUZZ_SUITE, EverySeedRunsWithoutAnUnexpectedError) {
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(HT_FUZZ_CORPUS_DIR)) {
    if (!entry.is_regular_file()) continue;
    const std::vector<std::uint8_t> bytes = readBytes(entry.path());
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW(LLVMFuzzerTestOneInput(bytes.data(), bytes.size()));
    ++files;
  }
  EXPECT_GE(files, 3u) << "the seed corpus " << HT_FUZZ_CORPUS_DIR << " should hold at least three inputs";
}

}  // namespace
