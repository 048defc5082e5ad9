// spirv_exact_float.cpp - see spirv_exact_float.h. Opcode, decoration, capability and execution-mode numbers:
// SPIR-V spec 3.32 (instructions), 3.20 (Decoration), 3.31 (Capability), 3.6 (Execution Mode).
#include "gpu/spirv_exact_float.h"

#include <algorithm>
#include <string>
#include <unordered_set>

#include "common/error.h"

namespace ht::gpu {
namespace {

constexpr std::size_t kHeaderWords = 5;
constexpr std::uint32_t kMagic = 0x07230203u;
constexpr std::uint32_t kOpCapability = 17, kOpEntryPoint = 15, kOpExecutionMode = 16, kOpDecorate = 71;
constexpr std::uint32_t kNoContraction = 42;
constexpr std::uint32_t kCapabilityDenormPreserve = 4464, kModeDenormPreserve = 4459;

bool isFloatArithmetic(std::uint32_t opcode) {
  switch (opcode) {
    case 127:  // OpFNegate
    case 129:  // OpFAdd
    case 131:  // OpFSub
    case 133:  // OpFMul
    case 136:  // OpFDiv
    case 140:  // OpFRem
    case 141:  // OpFMod
    case 142:  // OpVectorTimesScalar
    case 143:  // OpMatrixTimesScalar
    case 144:  // OpVectorTimesMatrix
    case 145:  // OpMatrixTimesVector
    case 146:  // OpMatrixTimesMatrix
    case 147:  // OpOuterProduct
    case 148:  // OpDot
      return true;
    default: return false;
  }
}

// Debug instructions of the module's debug section (not OpLine / OpNoLine, which may appear anywhere).
bool isDebug(std::uint32_t opcode) { return (opcode >= 2 && opcode <= 7) || opcode == 330; }

bool isAnnotation(std::uint32_t opcode) {
  // OpDecorate, OpMemberDecorate, OpDecorationGroup, OpGroupDecorate, OpGroupMemberDecorate, OpDecorateId,
  // OpDecorateString, OpMemberDecorateString.
  return (opcode >= 71 && opcode <= 75) || opcode == 332 || opcode == 5632 || opcode == 5633;
}

// What the walk over a module found, with the word offsets where new instructions of each section go.
struct Walk {
  std::vector<std::uint32_t> arithmeticResults;   // result ids of float arithmetic, in order
  std::unordered_set<std::uint32_t> decorated;    // ids already decorated NoContraction
  std::vector<std::uint32_t> entryPoints;         // entry point ids
  std::unordered_set<std::uint32_t> denormModes;  // entry points with DenormPreserve 32
  bool denormCapability = false;
  std::size_t afterCapabilities = kHeaderWords;  // after the last OpCapability
  std::size_t afterModes = kHeaderWords;         // after the last OpEntryPoint / OpExecutionMode
  std::size_t afterAnnotations = kHeaderWords;   // after the last debug instruction or annotation
};

Walk walk(std::span<const std::uint32_t> spirv) {
  if (spirv.size() < kHeaderWords || spirv[0] != kMagic)
    throw GpuError("SPIR-V module of " + std::to_string(spirv.size()) + " words has no SPIR-V header");
  Walk w;
  for (std::size_t at = kHeaderWords; at < spirv.size();) {
    const std::uint32_t words = spirv[at] >> 16, opcode = spirv[at] & 0xffffu;
    if (words == 0 || at + words > spirv.size())
      throw GpuError("SPIR-V instruction at word " + std::to_string(at) + " (opcode " + std::to_string(opcode) +
                     ") has a bad word count " + std::to_string(words));
    const std::size_t next = at + words;
    if (opcode == kOpCapability) {
      w.afterCapabilities = next;
      if (words >= 2 && spirv[at + 1] == kCapabilityDenormPreserve) w.denormCapability = true;
    }
    if (opcode == kOpEntryPoint && words >= 3) {
      w.entryPoints.push_back(spirv[at + 2]);
      w.afterModes = next;
    }
    if (opcode == kOpExecutionMode) {
      w.afterModes = next;
      if (words >= 4 && spirv[at + 2] == kModeDenormPreserve && spirv[at + 3] == 32)
        w.denormModes.insert(spirv[at + 1]);
    }
    if (isAnnotation(opcode) || isDebug(opcode)) w.afterAnnotations = next;
    if (opcode == kOpDecorate && words >= 3 && spirv[at + 2] == kNoContraction) w.decorated.insert(spirv[at + 1]);
    if (isFloatArithmetic(opcode) && words >= 3) w.arithmeticResults.push_back(spirv[at + 2]);
    at = next;
  }
  // A module without entry points or annotations: each section's insertion point is at least the one before.
  w.afterModes = std::max(w.afterModes, w.afterCapabilities);
  w.afterAnnotations = std::max(w.afterAnnotations, w.afterModes);
  return w;
}

}  // namespace

std::vector<std::uint32_t> makeFloatExact(std::span<const std::uint32_t> spirv, const ExactFloatOptions& options) {
  const Walk w = walk(spirv);
  std::vector<std::uint32_t> capability, modes, decorations;
  if (options.preserveDenormals) {
    for (std::uint32_t entry : w.entryPoints) {
      if (w.denormModes.count(entry) == 0)
        modes.insert(modes.end(), {(4u << 16) | kOpExecutionMode, entry, kModeDenormPreserve, 32u});
    }
    if (!w.denormCapability && !modes.empty()) capability = {(2u << 16) | kOpCapability, kCapabilityDenormPreserve};
  }
  if (options.noContraction) {
    for (std::uint32_t id : w.arithmeticResults) {
      if (w.decorated.count(id) == 0)
        decorations.insert(decorations.end(), {(3u << 16) | kOpDecorate, id, kNoContraction});
    }
  }
  // The three insertion points are in section order (capabilities, entry points and modes, annotations).
  std::vector<std::uint32_t> out;
  out.reserve(spirv.size() + capability.size() + modes.size() + decorations.size());
  auto copy = [&](std::size_t from, std::size_t to) {
    out.insert(out.end(), spirv.begin() + static_cast<std::ptrdiff_t>(from),
               spirv.begin() + static_cast<std::ptrdiff_t>(to));
  };
  copy(0, w.afterCapabilities);
  out.insert(out.end(), capability.begin(), capability.end());
  copy(w.afterCapabilities, w.afterModes);
  out.insert(out.end(), modes.begin(), modes.end());
  copy(w.afterModes, w.afterAnnotations);
  out.insert(out.end(), decorations.begin(), decorations.end());
  copy(w.afterAnnotations, spirv.size());
  return out;
}

ExactFloatCount countExactFloat(std::span<const std::uint32_t> spirv) {
  const Walk w = walk(spirv);
  ExactFloatCount c;
  c.arithmetic = static_cast<std::uint32_t>(w.arithmeticResults.size());
  for (std::uint32_t id : w.arithmeticResults) c.decorated += w.decorated.count(id) != 0 ? 1u : 0u;
  c.denormCapability = w.denormCapability;
  c.denormModes = static_cast<std::uint32_t>(w.denormModes.size());
  return c;
}

}  // namespace ht::gpu
