// panel_placement.cpp - see panel_placement.h.
#include "camera_models/panel_placement.h"

#include <regex>

namespace ht {

std::optional<PanelGeometry> parsePanelGeometry(std::string_view text) {
  static const std::regex kGeometry(R"((\d{1,5})x(\d{1,5})([+-]\d{1,5})([+-]\d{1,5}))");
  std::match_results<std::string_view::const_iterator> m;
  if (!std::regex_match(text.begin(), text.end(), m, kGeometry)) return std::nullopt;
  PanelGeometry g{std::stoi(m[3].str()), std::stoi(m[4].str()), static_cast<std::uint32_t>(std::stoul(m[1].str())),
                  static_cast<std::uint32_t>(std::stoul(m[2].str()))};
  if (g.width == 0 || g.height == 0) return std::nullopt;
  return g;
}

}  // namespace ht
