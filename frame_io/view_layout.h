// view_layout.h - how the views of a multi-view frame are arranged in files (frame_io/frame_package.h).
#pragma once
#include <optional>
#include <string>

namespace ht::frame_io {

enum class ViewLayout {
  Auto,   // a quilt when the views form one (quilt cameras, capture grids, oblique directions), else one file per view
  Quilt,  // all views tiled into one quilt image; refused when the views do not form a quilt
  Views,  // one file per view: <stem>_v00.png, <stem>_v01.png, ...
};

// "auto" | "quilt" | "views"; nullopt for anything else.
inline std::optional<ViewLayout> parseViewLayout(const std::string& text) {
  if (text == "auto") return ViewLayout::Auto;
  if (text == "quilt") return ViewLayout::Quilt;
  if (text == "views") return ViewLayout::Views;
  return std::nullopt;
}

}  // namespace ht::frame_io
