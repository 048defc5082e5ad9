// randr_reader.cpp - the RandR requests behind readRandrSnapshot: version check, screen resources, each output with
// its CRTC, mode, transform and EDID property, and the RandR 1.5 monitor list.
#include "present/randr_reader.h"

#include <xcb/randr.h>

#include <map>
#include <vector>

#include "present/edid.h"

namespace ht::present {
namespace {

constexpr std::uint32_t kFixedOne = 1u << 16;  // 1.0 in the 16.16 fixed point of xcb_render_transform_t
constexpr std::uint32_t kEdidMaxLongs = 256;   // 1 KiB: base block + extension blocks

void checkRandrVersion(const XConnection& x) {
  auto cookie = xcb_randr_query_version(x.get(), 1, 5);
  XReply<xcb_randr_query_version_reply_t> v(xcb_randr_query_version_reply(x.get(), cookie, nullptr));
  if (!v) throw PresentError("X display '" + x.name() + "' has no RandR extension");
  if (v->major_version < 1 || (v->major_version == 1 && v->minor_version < 5)) {
    throw PresentError("X display '" + x.name() + "' has RandR " + std::to_string(v->major_version) + "." +
                       std::to_string(v->minor_version) + ", monitors need RandR 1.5");
  }
}

double refreshOf(const xcb_randr_mode_info_t& mode) {
  double pixels = double(mode.htotal) * double(mode.vtotal);
  return pixels > 0 ? double(mode.dot_clock) / pixels : 0.0;
}

std::string atomName(const XConnection& x, xcb_atom_t atom) {
  XReply<xcb_get_atom_name_reply_t> r(xcb_get_atom_name_reply(x.get(), xcb_get_atom_name(x.get(), atom), nullptr));
  if (!r) return "atom" + std::to_string(atom);
  return std::string(xcb_get_atom_name_name(r.get()), static_cast<std::size_t>(xcb_get_atom_name_name_length(r.get())));
}

void readEdid(const XConnection& x, xcb_randr_output_t id, xcb_atom_t edidAtom, RandrOutput& out) {
  auto cookie = xcb_randr_get_output_property(x.get(), id, edidAtom, XCB_ATOM_ANY, 0, kEdidMaxLongs, 0, 0);
  XReply<xcb_randr_get_output_property_reply_t> r(xcb_randr_get_output_property_reply(x.get(), cookie, nullptr));
  if (!r || r->num_items == 0) return;  // no EDID
  if (r->format != 8) {
    out.edidProblem = "EDID property has format " + std::to_string(r->format) + ", not 8";
    return;
  }
  const auto* data = xcb_randr_get_output_property_data(r.get());
  try {
    out.edidMonitorName = parseEdid({data, r->num_items}).monitorName;
  } catch (const PresentError& e) { out.edidProblem = e.what(); }
}

bool identityTransform(const XConnection& x, xcb_randr_crtc_t crtc) {
  XReply<xcb_randr_get_crtc_transform_reply_t> r(
      xcb_randr_get_crtc_transform_reply(x.get(), xcb_randr_get_crtc_transform(x.get(), crtc), nullptr));
  if (!r) return true;
  const xcb_render_transform_t& t = r->current_transform;
  return t.matrix11 == kFixedOne && t.matrix22 == kFixedOne && t.matrix33 == kFixedOne && t.matrix12 == 0 &&
         t.matrix13 == 0 && t.matrix21 == 0 && t.matrix23 == 0 && t.matrix31 == 0 && t.matrix32 == 0;
}

void readCrtc(const XConnection& x, xcb_randr_crtc_t crtc, xcb_timestamp_t stamp,
              const std::map<xcb_randr_mode_t, xcb_randr_mode_info_t>& modes, RandrOutput& out) {
  XReply<xcb_randr_get_crtc_info_reply_t> c(
      xcb_randr_get_crtc_info_reply(x.get(), xcb_randr_get_crtc_info(x.get(), crtc, stamp), nullptr));
  if (!c) return;
  out.crtc = Rect{c->x, c->y, c->width, c->height};
  out.rotation = c->rotation;
  auto mode = modes.find(c->mode);
  if (mode != modes.end()) {
    out.modeWidth = mode->second.width;
    out.modeHeight = mode->second.height;
    out.refreshHz = refreshOf(mode->second);
  }
  out.identityTransform = identityTransform(x, crtc);
}

std::map<xcb_randr_output_t, std::string> readOutputs(const XConnection& x, RandrSnapshot& snapshot) {
  auto cookie = xcb_randr_get_screen_resources_current(x.get(), x.root());
  XReply<xcb_randr_get_screen_resources_current_reply_t> res(
      xcb_randr_get_screen_resources_current_reply(x.get(), cookie, nullptr));
  if (!res) throw PresentError("X display '" + x.name() + "': RandR screen resources unavailable");
  std::map<xcb_randr_mode_t, xcb_randr_mode_info_t> modes;
  const xcb_randr_mode_info_t* modeInfo = xcb_randr_get_screen_resources_current_modes(res.get());
  for (int i = 0; i < xcb_randr_get_screen_resources_current_modes_length(res.get()); ++i)
    modes[modeInfo[i].id] = modeInfo[i];
  const xcb_atom_t edidAtom = x.atom("EDID");
  std::map<xcb_randr_output_t, std::string> names;
  const xcb_randr_output_t* ids = xcb_randr_get_screen_resources_current_outputs(res.get());
  for (int i = 0; i < xcb_randr_get_screen_resources_current_outputs_length(res.get()); ++i) {
    auto infoCookie = xcb_randr_get_output_info(x.get(), ids[i], res->config_timestamp);
    XReply<xcb_randr_get_output_info_reply_t> info(xcb_randr_get_output_info_reply(x.get(), infoCookie, nullptr));
    if (!info) continue;
    RandrOutput out;
    out.name.assign(reinterpret_cast<const char*>(xcb_randr_get_output_info_name(info.get())),
                    static_cast<std::size_t>(xcb_randr_get_output_info_name_length(info.get())));
    out.connected = info->connection == XCB_RANDR_CONNECTION_CONNECTED;
    if (info->crtc != XCB_NONE) readCrtc(x, info->crtc, res->config_timestamp, modes, out);
    readEdid(x, ids[i], edidAtom, out);
    names[ids[i]] = out.name;
    snapshot.outputs.push_back(std::move(out));
  }
  return names;
}

void readMonitors(const XConnection& x, const std::map<xcb_randr_output_t, std::string>& outputNames,
                  RandrSnapshot& snapshot) {
  XReply<xcb_randr_get_monitors_reply_t> r(
      xcb_randr_get_monitors_reply(x.get(), xcb_randr_get_monitors(x.get(), x.root(), 1), nullptr));
  if (!r) throw PresentError("X display '" + x.name() + "': RandR monitor list unavailable");
  for (auto it = xcb_randr_get_monitors_monitors_iterator(r.get()); it.rem; xcb_randr_monitor_info_next(&it)) {
    const xcb_randr_monitor_info_t* m = it.data;
    RandrMonitor monitor;
    monitor.name = atomName(x, m->name);
    monitor.rect = Rect{m->x, m->y, m->width, m->height};
    monitor.primary = m->primary != 0;
    monitor.automatic = m->automatic != 0;
    const xcb_randr_output_t* outs = xcb_randr_monitor_info_outputs(m);
    for (int i = 0; i < xcb_randr_monitor_info_outputs_length(m); ++i) {
      auto name = outputNames.find(outs[i]);
      if (name != outputNames.end()) monitor.outputs.push_back(name->second);
    }
    snapshot.monitors.push_back(std::move(monitor));
  }
}

}  // namespace

RandrSnapshot readRandrSnapshot(const XConnection& x) {
  checkRandrVersion(x);
  RandrSnapshot snapshot;
  auto outputNames = readOutputs(x, snapshot);
  readMonitors(x, outputNames, snapshot);
  return snapshot;
}

std::uint8_t selectRandrEvents(const XConnection& x) {
  const xcb_query_extension_reply_t* ext = xcb_get_extension_data(x.get(), &xcb_randr_id);
  if (!ext || !ext->present) throw PresentError("X display '" + x.name() + "' has no RandR extension");
  xcb_randr_select_input(x.get(), x.root(),
                         XCB_RANDR_NOTIFY_MASK_SCREEN_CHANGE | XCB_RANDR_NOTIFY_MASK_OUTPUT_CHANGE |
                             XCB_RANDR_NOTIFY_MASK_CRTC_CHANGE | XCB_RANDR_NOTIFY_MASK_OUTPUT_PROPERTY);
  xcb_flush(x.get());
  return ext->first_event;
}

}  // namespace ht::present
