// json_fields.h - reading typed fields out of display-config / visual.json objects with errors that name the file,
// the field path and the offending value (ht::ConfigError). Internal to camera_models.
#pragma once
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

namespace ht::detail {

// Where a JSON object came from: the file name for errors and the dotted path of the object inside it
// ("" for the top level, "calibration" for an embedded visual.json, "camera" ...).
struct JsonLocation {
  std::string file;
  std::string prefix;
  std::string field(std::string_view key) const;  // prefix + "." + key (or key at top level)
  JsonLocation child(std::string_view key) const { return {file, field(key)}; }
};

// Parses JSON text; a syntax error becomes ConfigError(file, "(json)", "line L, column C", "expected valid JSON ...").
nlohmann::json parseJsonText(std::string_view text, const std::string& file);

// Reads a whole file; a missing / unreadable file becomes ConfigError(file, field, quoted path, expected).
std::string readTextFile(const std::string& path, const std::string& errorFile, const std::string& field,
                         const std::string& expectedWhat);

// The value as it appears in the file (compact JSON, shortened), or "(missing)".
std::string valueText(const nlohmann::json* value);

// Numeric fields may be bare numbers or vendor-wrapped {"value": x} (LKG-Toolkit Calibration.cs ToJSON).
const nlohmann::json& unwrapValue(const nlohmann::json& value);

const nlohmann::json* findField(const nlohmann::json& object, std::string_view key);

// Finite number; `allowWrapped` accepts {"value": x}. Missing -> ConfigError "(missing)" unless a default is given.
double requireNumber(const JsonLocation& at, const nlohmann::json& object, std::string_view key, bool allowWrapped,
                     const std::string& expected);
std::optional<double> optionalNumber(const JsonLocation& at, const nlohmann::json& object, std::string_view key,
                                     bool allowWrapped, const std::string& expected);

// Integer in [lo, hi] (a float value must be integral, e.g. 1536.0).
std::optional<long long> optionalInteger(const JsonLocation& at, const nlohmann::json& object, std::string_view key,
                                         bool allowWrapped, long long lo, long long hi);
long long requireInteger(const JsonLocation& at, const nlohmann::json& object, std::string_view key, bool allowWrapped,
                         long long lo, long long hi);

// Boolean as true/false or 0/1 (bare or wrapped).
std::optional<bool> optionalFlag(const JsonLocation& at, const nlohmann::json& object, std::string_view key);
bool requireFlag(const JsonLocation& at, const nlohmann::json& object, std::string_view key);

std::optional<std::string> optionalString(const JsonLocation& at, const nlohmann::json& object, std::string_view key);

[[noreturn]] void throwFieldError(const JsonLocation& at, std::string_view key, const nlohmann::json* value,
                                  const std::string& expected);

// Throws a ConfigError for the first key of `object` not in `allowed`, listing the allowed keys: typos in our
// config sections must not pass silently.
void rejectUnknownKeys(const JsonLocation& at, const nlohmann::json& object,
                       std::initializer_list<std::string_view> allowed);

// Required finite number > 0; `expected` is the error's "expected ..." text.
double requirePositiveNumber(const JsonLocation& at, const nlohmann::json& object, std::string_view key,
                             const std::string& expected);

// Formats a double for error messages ("0.001", "1e+06").
std::string formatNumber(double value);

}  // namespace ht::detail
