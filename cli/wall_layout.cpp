// wall_layout.cpp - see wall_layout.h.
#include "cli/wall_layout.h"

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "common/error.h"
#include "common/json_nesting.h"
#include "present/monitor_picker.h"
#include "present/present_error.h"

namespace ht::cli {
namespace {

using nlohmann::json;
constexpr std::size_t kMaxLayoutBytes = 1 << 20;

[[noreturn]] void fail(const std::string& source, const std::string& field, const std::string& problem) {
  throw UsageError("holotrace wall: layout " + source + ": '" + field + "' " + problem);
}

std::uint32_t projectorIndex(const json& value, const std::string& source, const std::string& field,
                             std::uint32_t views) {
  if (!value.is_number_unsigned() || value.get<std::uint64_t>() >= views) {
    fail(source, field, "= " + value.dump() + ": expected a projector index 0-" + std::to_string(views - 1));
  }
  return value.get<std::uint32_t>();
}

std::vector<std::uint32_t> parseProjectors(const json& entry, const std::string& source, const std::string& field,
                                           std::uint32_t views) {
  if (!entry.contains("projectors")) fail(source, field, "is missing (a list of view indices or {first, count})");
  const json& p = entry["projectors"];
  std::vector<std::uint32_t> out;
  if (p.is_array()) {
    for (std::size_t i = 0; i < p.size(); ++i)
      out.push_back(projectorIndex(p[i], source, field + "[" + std::to_string(i) + "]", views));
  } else if (p.is_object() && p.contains("first") && p.contains("count") && p["count"].is_number_unsigned()) {
    const std::uint32_t first = projectorIndex(p["first"], source, field + ".first", views);
    const std::uint64_t count = p["count"].get<std::uint64_t>();
    if (count == 0 || first + count > views) {
      fail(source, field + ".count",
           "= " + p["count"].dump() + ": the range must hold 1-" + std::to_string(views - first) + " projectors from " +
               std::to_string(first));
    }
    for (std::uint32_t v = first; v < first + count; ++v) out.push_back(v);
  } else {
    fail(source, field, "= " + p.dump() + ": expected a list of view indices or {\"first\": F, \"count\": N}");
  }
  if (out.empty()) fail(source, field, "is empty: every rank shows at least one projector");
  return out;
}

std::optional<std::string> optionalText(const json& entry, const char* key, const std::string& source,
                                        const std::string& at) {
  if (!entry.contains(key)) return std::nullopt;
  if (!entry[key].is_string() || entry[key].get<std::string>().empty())
    fail(source, at + "." + key, "= " + entry[key].dump() + ": expected a non-empty string");
  return entry[key].get<std::string>();
}

RankScreen parseRank(const json& entry, std::size_t r, const std::string& source, std::uint32_t views) {
  const std::string at = "ranks[" + std::to_string(r) + "]";
  if (!entry.is_object()) fail(source, at, "= " + entry.dump() + ": expected an object");
  RankScreen screen;
  screen.projectors = parseProjectors(entry, source, at + ".projectors", views);
  screen.columns = std::uint32_t(screen.projectors.size());
  if (entry.contains("columns")) {
    const json& c = entry["columns"];
    if (!c.is_number_unsigned() || c.get<std::uint64_t>() == 0 || c.get<std::uint64_t>() > screen.projectors.size())
      fail(source, at + ".columns", "= " + c.dump() + ": expected 1-" + std::to_string(screen.projectors.size()));
    screen.columns = c.get<std::uint32_t>();
  }
  screen.monitor = optionalText(entry, "monitor", source, at);
  screen.xDisplay = optionalText(entry, "x_display", source, at);
  if (auto geometry = optionalText(entry, "geometry", source, at)) {
    try {
      screen.geometry = present::parseGeometry(*geometry);
    } catch (const present::PresentError& e) { fail(source, at + ".geometry", "= \"" + *geometry + "\": " + e.what()); }
  }
  if (screen.monitor && screen.geometry) fail(source, at, "gives both 'monitor' and 'geometry'; give one");
  return screen;
}

}  // namespace

WallLayout parseWallLayout(const std::string& text, const std::string& source, std::uint32_t views,
                           std::uint32_t rankCount) {
  if (auto v = findJsonNestingViolation(text))
    fail(source, "(file)",
         "nests deeper than " + std::to_string(kMaxJsonNesting) + " levels at line " + std::to_string(v->line));
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) { fail(source, "(file)", std::string("is not valid JSON: ") + e.what()); }
  if (!doc.is_object() || !doc.contains("ranks") || !doc["ranks"].is_array())
    fail(source, "ranks", "is missing: expected {\"ranks\": [{\"projectors\": [...]}, ...]}, one entry per rank");
  const json& ranks = doc["ranks"];
  if (ranks.size() != rankCount) {
    fail(source, "ranks",
         "has " + std::to_string(ranks.size()) + " entries but the job has " + std::to_string(rankCount) +
             " rank(s): give one entry per rank (mpirun -np)");
  }
  WallLayout layout{{}, source};
  std::set<std::uint32_t> seen;
  for (std::size_t r = 0; r < ranks.size(); ++r) {
    layout.ranks.push_back(parseRank(ranks[r], r, source, views));
    for (std::uint32_t v : layout.ranks.back().projectors) {
      if (!seen.insert(v).second)
        fail(source, "ranks[" + std::to_string(r) + "].projectors",
             "names projector " + std::to_string(v) + " a second time: every projector belongs to one rank");
    }
  }
  return layout;
}

WallLayout loadWallLayout(const std::filesystem::path& path, std::uint32_t views, std::uint32_t rankCount) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UsageError("holotrace wall: option '--layout' = '" + path.string() + "': cannot open the file");
  std::string text(kMaxLayoutBytes + 1, '\0');
  in.read(text.data(), std::streamsize(text.size()));
  text.resize(std::size_t(in.gcount()));
  if (text.size() > kMaxLayoutBytes)
    fail(path.string(), "(file)", "is larger than " + std::to_string(kMaxLayoutBytes) + " bytes");
  return parseWallLayout(text, path.string(), views, rankCount);
}

WallLayout defaultWallLayout(std::uint32_t views, std::uint32_t rankCount) {
  if (rankCount > views) {
    throw UsageError("holotrace wall: the display has " + std::to_string(views) + " projector(s)/view(s) but the job " +
                     std::to_string(rankCount) + " ranks: start at most " + std::to_string(views) +
                     " ranks, or give --layout");
  }
  WallLayout layout{{}, "default layout"};
  std::uint32_t next = 0;
  for (std::uint32_t r = 0; r < rankCount; ++r) {
    RankScreen screen;
    const std::uint32_t count = views / rankCount + (r < views % rankCount ? 1 : 0);
    for (std::uint32_t i = 0; i < count; ++i) screen.projectors.push_back(next++);
    screen.columns = count;
    layout.ranks.push_back(screen);
  }
  return layout;
}

std::string describeWallLayout(const WallLayout& layout) {
  std::ostringstream s;
  for (std::size_t r = 0; r < layout.ranks.size(); ++r) {
    const RankScreen& screen = layout.ranks[r];
    s << "rank " << r << ":";
    for (std::uint32_t v : screen.projectors) s << " " << v;
    s << " columns " << screen.columns << " monitor " << screen.monitor.value_or("-") << " geometry "
      << (screen.geometry ? present::describeRect(*screen.geometry) : "-") << " x " << screen.xDisplay.value_or("-")
      << "\n";
  }
  return s.str();
}

}  // namespace ht::cli
