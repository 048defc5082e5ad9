// randr_snapshot.cpp - small helpers over the RandR data.
#include "present/randr_snapshot.h"

namespace ht::present {

std::string describeRect(const Rect& rect) {
  auto sign = [](std::int32_t v) { return (v < 0 ? "" : "+") + std::to_string(v); };
  return std::to_string(rect.width) + "x" + std::to_string(rect.height) + sign(rect.x) + sign(rect.y);
}

const RandrOutput* RandrSnapshot::output(const std::string& name) const {
  for (const RandrOutput& o : outputs) {
    if (o.name == name) return &o;
  }
  return nullptr;
}

}  // namespace ht::present
