// json_fields.cpp - typed JSON field access with ConfigError reporting (see json_fields.h).
#include "camera_models/json_fields.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "common/error.h"

namespace ht::detail {

using nlohmann::json;

std::string JsonLocation::field(std::string_view key) const {
  if (prefix.empty()) return std::string(key);
  if (key.empty()) return prefix;
  if (!key.empty() && key.front() == '[') return prefix + std::string(key);
  return prefix + "." + std::string(key);
}

namespace {

// 1-based line and column of byte offset `byte` (nlohmann reports the 1-based position of the last byte read).
std::pair<std::size_t, std::size_t> lineAndColumn(std::string_view text, std::size_t byte) {
  std::size_t line = 1, column = 1;
  std::size_t end = std::min(byte > 0 ? byte - 1 : 0, text.size());
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

}  // namespace

json parseJsonText(std::string_view text, const std::string& file) {
  try {
    return json::parse(text.begin(), text.end());
  } catch (const json::parse_error& e) {
    auto [line, column] = lineAndColumn(text, e.byte);
    throw ConfigError(file, "(json)", "line " + std::to_string(line) + ", column " + std::to_string(column),
                      std::string("expected valid JSON; parser said: ") + e.what());
  } catch (const json::exception& e) {  // e.g. out_of_range 406 "number overflow parsing '1e999'"
    throw ConfigError(file, "(json)", "(not representable)",
                      std::string("expected valid JSON with finite numbers; parser said: ") + e.what());
  }
}

std::string readTextFile(const std::string& path, const std::string& errorFile, const std::string& field,
                         const std::string& expectedWhat) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(errorFile, field, "\"" + path + "\"", expectedWhat);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ConfigError(errorFile, field, "\"" + path + "\"", expectedWhat + " (read failed)");
  return text.str();
}

std::string valueText(const json* value) {
  if (value == nullptr) return "(missing)";
  std::string text = value->dump();
  constexpr std::size_t kMaxLength = 80;
  if (text.size() > kMaxLength) text = text.substr(0, kMaxLength - 3) + "...";
  return text;
}

std::string formatNumber(double value) {
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

const json& unwrapValue(const json& value) {
  if (value.is_object()) {
    auto it = value.find("value");
    if (it != value.end()) return *it;
  }
  return value;
}

const json* findField(const json& object, std::string_view key) {
  auto it = object.find(std::string(key));
  return it == object.end() ? nullptr : &*it;
}

void throwFieldError(const JsonLocation& at, std::string_view key, const json* value, const std::string& expected) {
  throw ConfigError(at.file, at.field(key), valueText(value), expected);
}

std::optional<double> optionalNumber(const JsonLocation& at, const json& object, std::string_view key,
                                     bool allowWrapped, const std::string& expected) {
  const json* field = findField(object, key);
  if (field == nullptr) return std::nullopt;
  const json& value = allowWrapped ? unwrapValue(*field) : *field;
  if (!value.is_number()) throwFieldError(at, key, field, expected);
  double number = value.get<double>();
  if (!std::isfinite(number)) throwFieldError(at, key, field, expected);
  return number;
}

double requireNumber(const JsonLocation& at, const json& object, std::string_view key, bool allowWrapped,
                     const std::string& expected) {
  std::optional<double> number = optionalNumber(at, object, key, allowWrapped, expected);
  if (!number) throwFieldError(at, key, nullptr, expected + " (the field is required)");
  return *number;
}

std::optional<long long> optionalInteger(const JsonLocation& at, const json& object, std::string_view key,
                                         bool allowWrapped, long long lo, long long hi) {
  std::string expected = "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  std::optional<double> number = optionalNumber(at, object, key, allowWrapped, expected);
  if (!number) return std::nullopt;
  if (*number != std::floor(*number) || *number < double(lo) || *number > double(hi))
    throwFieldError(at, key, findField(object, key), expected);
  return static_cast<long long>(*number);
}

long long requireInteger(const JsonLocation& at, const json& object, std::string_view key, bool allowWrapped,
                         long long lo, long long hi) {
  std::optional<long long> number = optionalInteger(at, object, key, allowWrapped, lo, hi);
  if (!number)
    throwFieldError(
        at, key, nullptr,
        "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (the field is required)");
  return *number;
}

std::optional<bool> optionalFlag(const JsonLocation& at, const json& object, std::string_view key) {
  const json* field = findField(object, key);
  if (field == nullptr) return std::nullopt;
  const json& value = unwrapValue(*field);
  if (value.is_boolean()) return value.get<bool>();
  if (value.is_number()) {
    double number = value.get<double>();
    if (number == 0.0) return false;
    if (number == 1.0) return true;
  }
  throwFieldError(at, key, field, "expected 0, 1, true or false");
}

bool requireFlag(const JsonLocation& at, const json& object, std::string_view key) {
  std::optional<bool> flag = optionalFlag(at, object, key);
  if (!flag) throwFieldError(at, key, nullptr, "expected 0, 1, true or false (the field is required)");
  return *flag;
}

std::optional<std::string> optionalString(const JsonLocation& at, const json& object, std::string_view key) {
  const json* field = findField(object, key);
  if (field == nullptr) return std::nullopt;
  const json& value = unwrapValue(*field);
  if (value.is_string()) return value.get<std::string>();
  throwFieldError(at, key, field, "expected a string");
}

void rejectUnknownKeys(const JsonLocation& at, const nlohmann::json& object,
                       std::initializer_list<std::string_view> allowed) {
  for (const auto& [key, value] : object.items()) {
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::string list;
    for (std::string_view k : allowed) list += (list.empty() ? "" : ", ") + std::string(k);
    throwFieldError(at, key, &value, "unknown key; expected one of: " + list);
  }
}

double requirePositiveNumber(const JsonLocation& at, const nlohmann::json& object, std::string_view key,
                             const std::string& expected) {
  const double value = requireNumber(at, object, key, false, expected);
  if (!(value > 0.0)) throwFieldError(at, key, findField(object, key), expected);
  return value;
}

}  // namespace ht::detail
