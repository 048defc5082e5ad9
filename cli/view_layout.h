// view_layout.h - how a multi-view frame is written (cli/frame_outputs.h).
#pragma once
#include <optional>
#include <string>

namespace ht::cli {

enum class ViewLayout {
  Auto,   // quilt when the views form one (quilt cameras, capture grids), else a PNG per view
  Quilt,  // all views tiled into one quilt image
  Views,  // one PNG per view: <stem>_v00.png, <stem>_v01.png, ...
};

// "auto" | "quilt" | "views"; nullopt for anything else.
inline std::optional<ViewLayout> parseViewLayout(const std::string& text) {
  if (text == "auto") return ViewLayout::Auto;
  if (text == "quilt") return ViewLayout::Quilt;
  if (text == "views") return ViewLayout::Views;
  return std::nullopt;
}

}  // namespace ht::cli
