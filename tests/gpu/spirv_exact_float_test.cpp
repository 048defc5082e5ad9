// spirv_exact_float_test.cpp - the pass that makes drivers round as the C++ does (gpu/spirv_exact_float.h) on the
// renderer's own SPIR-V: every float arithmetic result decorated once, denormals kept per entry point, nothing else
// changed, bad modules refused. That drivers then agree with the C++ references is what the parity tests check on
// each driver they run on.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/error.h"
#include "gpu/compute_pipeline.h"
#include "gpu/spirv_exact_float.h"

namespace ht::gpu {
namespace {

constexpr ExactFloatOptions kBoth{true, true};

// The module's instructions other than those the pass adds, in order.
std::vector<std::uint32_t> withoutAdded(std::span<const std::uint32_t> spirv) {
  std::vector<std::uint32_t> out(spirv.begin(), spirv.begin() + 5);
  for (std::size_t at = 5; at < spirv.size();) {
    const std::uint32_t words = spirv[at] >> 16, opcode = spirv[at] & 0xffffu;
    const bool added = (opcode == 71u && words == 3 && spirv[at + 2] == 42u) ||    // NoContraction
                       (opcode == 17u && words == 2 && spirv[at + 1] == 4464u) ||  // Capability DenormPreserve
                       (opcode == 16u && words == 4 && spirv[at + 2] == 4459u);    // ExecutionMode DenormPreserve
    if (!added) out.insert(out.end(), spirv.begin() + at, spirv.begin() + at + words);
    at += words;
  }
  return out;
}

TEST(SpirvExactFloat, EveryFloatArithmeticResultOfEveryPassIsDecoratedOnceAndDenormalsKept) {
  int withArithmetic = 0;
  for (int i = 0; i <= static_cast<int>(ShaderId::MarkAccumulated); ++i) {  // every pass
    const auto id = static_cast<ShaderId>(i);
    const std::span<const std::uint32_t> embedded = embeddedSpirv(id);
    const ExactFloatCount before = countExactFloat(embedded);
    // glslang decorates what the shared headers mark HT_PRECISE, not the rest.
    if (before.arithmetic > 0) {
      ++withArithmetic;
      EXPECT_LT(before.decorated, before.arithmetic) << shaderName(id);
    }
    EXPECT_FALSE(before.denormCapability) << shaderName(id);

    const std::vector<std::uint32_t> exact = makeFloatExact(embedded, kBoth);
    const ExactFloatCount after = countExactFloat(exact);
    EXPECT_EQ(after.arithmetic, before.arithmetic) << shaderName(id);
    EXPECT_EQ(after.decorated, after.arithmetic) << shaderName(id);
    EXPECT_TRUE(after.denormCapability) << shaderName(id);
    EXPECT_EQ(after.denormModes, 1u) << shaderName(id);
    EXPECT_EQ(exact.size(), embedded.size() + 3 * (before.arithmetic - before.decorated) + 2 + 4) << shaderName(id);
    EXPECT_EQ(exact[3], embedded[3]) << "the id bound must not change";
    // Only those instructions were added, and a second pass adds none.
    EXPECT_EQ(withoutAdded(exact), withoutAdded(embedded)) << shaderName(id);
    EXPECT_EQ(makeFloatExact(exact, kBoth), exact) << shaderName(id);
  }
  EXPECT_EQ(withArithmetic, 11) << "of the 13 passes, all but prepare and the interleave do float arithmetic";
}

TEST(SpirvExactFloat, EachPartCanBeLeftOut) {
  const std::span<const std::uint32_t> embedded = embeddedSpirv(ShaderId::Shade);
  const std::vector<std::uint32_t> same = makeFloatExact(embedded, {false, false});
  EXPECT_EQ(same, std::vector<std::uint32_t>(embedded.begin(), embedded.end()));
  const ExactFloatCount decoratedOnly = countExactFloat(makeFloatExact(embedded, {true, false}));
  EXPECT_EQ(decoratedOnly.decorated, decoratedOnly.arithmetic);
  EXPECT_FALSE(decoratedOnly.denormCapability);
  const ExactFloatCount denormOnly = countExactFloat(makeFloatExact(embedded, {false, true}));
  EXPECT_LT(denormOnly.decorated, denormOnly.arithmetic);
  EXPECT_TRUE(denormOnly.denormCapability);
}

// Logical layout (SPIR-V spec 2.4): capabilities first, execution modes before the debug section, decorations
// after it and before the first type.
TEST(SpirvExactFloat, AddedInstructionsKeepTheModulesSectionOrder) {
  const std::vector<std::uint32_t> exact = makeFloatExact(embeddedSpirv(ShaderId::TraceClosest), kBoth);
  std::size_t lastCapability = 0, firstOther = 0, lastMode = 0, firstDebug = 0, lastDecorate = 0, firstType = 0;
  for (std::size_t at = 5; at < exact.size(); at += exact[at] >> 16) {
    const std::uint32_t opcode = exact[at] & 0xffffu;
    if (opcode == 17u) lastCapability = at;
    if (opcode != 17u && firstOther == 0) firstOther = at;
    if (opcode == 16u) lastMode = at;
    if ((opcode == 3u || opcode == 5u) && firstDebug == 0) firstDebug = at;
    if (opcode == 71u) lastDecorate = at;
    if (opcode >= 19u && opcode <= 39u && firstType == 0) firstType = at;
  }
  ASSERT_GT(firstType, 0u);
  EXPECT_LT(lastCapability, firstOther);
  if (firstDebug != 0) { EXPECT_LT(lastMode, firstDebug); }
  EXPECT_LT(lastDecorate, firstType);
}

// spirv-val (SPIRV-Tools, scripts/install-deps.sh) accepts every pass with both parts added, for Vulkan 1.2: the
// DenormPreserve capability and execution mode included, which lavapipe never gets (it cannot keep denormals), so only
// a GPU that can would otherwise try them.
TEST(SpirvExactFloat, EveryPassStaysValidForSpirvVal) {
  if (std::system("spirv-val --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "spirv-val not installed (spirv-tools)";
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("ht_exact_float_" + std::to_string(::getpid()) + ".spv");
  for (int i = 0; i <= static_cast<int>(ShaderId::MarkAccumulated); ++i) {
    const auto id = static_cast<ShaderId>(i);
    const std::vector<std::uint32_t> exact = makeFloatExact(embeddedSpirv(id), kBoth);
    {
      std::ofstream out(file, std::ios::binary);
      out.write(reinterpret_cast<const char*>(exact.data()), static_cast<std::streamsize>(exact.size() * 4));
    }
    const std::string command = "spirv-val --target-env vulkan1.2 " + file.string() + " 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << shaderName(id);
  }
  std::filesystem::remove(file);
}

TEST(SpirvExactFloat, MalformedModulesAreRefusedNotWalkedPastTheirEnd) {
  EXPECT_THROW(makeFloatExact(std::vector<std::uint32_t>{1, 2, 3}, kBoth), GpuError);
  EXPECT_EQ(makeFloatExact(std::vector<std::uint32_t>{0x07230203u, 0x10000, 0, 10, 0}, kBoth).size(), 5u)
      << "a header alone is a module without instructions";
  const std::span<const std::uint32_t> resolve = embeddedSpirv(ShaderId::Resolve);
  std::vector<std::uint32_t> truncated(resolve.begin(), resolve.end());
  truncated.push_back((4u << 16) | 1u);  // an instruction of 4 words with 1 left
  truncated.push_back(0u);
  EXPECT_THROW(makeFloatExact(truncated, kBoth), GpuError);
  std::vector<std::uint32_t> zeroCount(resolve.begin(), resolve.end());
  zeroCount[5] &= 0xffffu;
  EXPECT_THROW(makeFloatExact(zeroCount, kBoth), GpuError);
}

}  // namespace
}  // namespace ht::gpu
