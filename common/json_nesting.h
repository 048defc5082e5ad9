// json_nesting.h - the one JSON nesting limit of holotrace, checked on the raw text BEFORE any parser or printer
// sees it. nlohmann::json parses deep input fine but prints (dump(), error messages) and converts recursively, and
// tinygltf converts `extras`/`extensions` recursively: a file nested ~100,000 levels deep overflowed the stack
// (docs/SERVICE.md "Limits"). The scan is a single pass with O(1) memory, so it is safe on any input, valid or not.
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace ht {

// Deepest array/object nesting any holotrace JSON input (display config, visual.json, daemon config, glTF) may have.
// Our own formats need at most 5 levels; glTF files in the wild stay well below 32.
inline constexpr std::size_t kMaxJsonNesting = 64;

struct JsonNestingViolation {
  std::size_t line = 1, column = 1;  // 1-based position of the bracket that went one level too deep
};

// Counts '[' / '{' outside strings (escapes honoured); returns where the nesting first exceeds `maxDepth`.
inline std::optional<JsonNestingViolation> findJsonNestingViolation(std::string_view text,
                                                                    std::size_t maxDepth = kMaxJsonNesting) {
  std::size_t depth = 0, line = 1, column = 0;
  bool inString = false, escaped = false;
  for (const char c : text) {
    ++column;
    if (c == '\n') ++line, column = 0;
    if (inString) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        inString = false;
      continue;
    }
    if (c == '"')
      inString = true;
    else if (c == '[' || c == '{') {
      if (++depth > maxDepth) return JsonNestingViolation{line, column};
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return std::nullopt;
}

// The message every caller puts in its own error type: "JSON nesting deeper than 64 levels at line L, column C".
inline std::string jsonNestingMessage(const JsonNestingViolation& at, std::size_t maxDepth = kMaxJsonNesting) {
  return "JSON nesting deeper than " + std::to_string(maxDepth) + " levels at line " + std::to_string(at.line) +
         ", column " + std::to_string(at.column);
}

}  // namespace ht
