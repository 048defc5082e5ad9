// image_reading.cpp - see image_reading.h.
#include "frame_io/image_reading.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <memory>

#include "common/error.h"
#include "common/srgb.h"

namespace ht::frame_io {
namespace {

constexpr int kNoChannel = -1;
using ChannelIndices = std::array<int, 4>;  // R, G, B, A in the file; A may be kNoChannel

[[noreturn]] void fail(const std::string& source, const std::string& problem) {
  throw IoError("cannot read image '" + source + "': " + problem);
}

std::string oiioDetail(std::string detail) {
  if (detail.empty()) detail = OIIO::geterror();
  return detail.empty() ? "unknown OpenImageIO error" : detail;
}

SampleType sampleTypeOf(OIIO::TypeDesc type) {
  if (type == OIIO::TypeDesc::UINT8) return SampleType::UInt8;
  if (type == OIIO::TypeDesc::UINT16) return SampleType::UInt16;
  if (type == OIIO::TypeDesc::HALF) return SampleType::Half;
  if (type == OIIO::TypeDesc::FLOAT) return SampleType::Float;
  return SampleType::Other;
}

std::vector<std::string> multiViewNames(const OIIO::ImageSpec& spec) {
  const OIIO::ParamValue* views = spec.find_attribute("multiView");
  if (views == nullptr || views->type().basetype != OIIO::TypeDesc::STRING) return {};
  std::vector<std::string> names;
  const auto* strings = static_cast<const char* const*>(views->data());
  const std::size_t count = std::size_t(views->nvalues()) * views->type().numelements();
  for (std::size_t i = 0; i < count; ++i) names.emplace_back(strings[i]);
  return names;
}

ImageAttributes stringAttributes(const OIIO::ImageSpec& spec) {
  ImageAttributes attributes;
  for (const OIIO::ParamValue& p : spec.extra_attribs) {
    if (p.type() == OIIO::TypeDesc::STRING) attributes.emplace_back(p.name().string(), p.get_string());
  }
  return attributes;
}

// The R, G, B, A channels of view `view` named "<view>.X" (the default view may use bare names).
ChannelIndices viewChannels(const std::string& source, const OIIO::ImageSpec& spec, const std::string& view,
                            bool isDefault) {
  ChannelIndices index{};
  const char* names[4] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; ++c) {
    index[c] = spec.channelindex(view + "." + names[c]);
    if (index[c] < 0 && isDefault) index[c] = spec.channelindex(names[c]);
    if (index[c] < 0 && c < 3)
      fail(source, "multiView view '" + view + "' has no channel '" + view + "." + names[c] + "'");
  }
  return index;
}

// R, G, B, A of a one-view image: by name, grey "Y", else by position.
ChannelIndices imageChannels(const std::string& source, const OIIO::ImageSpec& spec) {
  const int r = spec.channelindex("R"), g = spec.channelindex("G"), b = spec.channelindex("B");
  const int a = spec.channelindex("A") >= 0 ? spec.channelindex("A") : spec.alpha_channel;
  if (r >= 0 && g >= 0 && b >= 0) return {r, g, b, a};
  if (const int y = spec.channelindex("Y"); y >= 0) return {y, y, y, a};
  switch (spec.nchannels) {
    case 1: return {0, 0, 0, kNoChannel};
    case 2: return {0, 0, 0, 1};
    case 3: return {0, 1, 2, kNoChannel};
    case 4: return {0, 1, 2, 3};
    default: fail(source, std::to_string(spec.nchannels) + " channels and none named R, G, B or Y (expected RGB(A))");
  }
}

void checkSize(const std::string& source, const OIIO::ImageSpec& spec, std::uint64_t views) {
  if (spec.deep || spec.depth > 1)
    fail(source, std::string(spec.deep ? "deep" : "volume") + " image (expected flat 2D)");
  if (spec.x != 0 || spec.y != 0)
    fail(source, "data window starts at " + std::to_string(spec.x) + "," + std::to_string(spec.y) + " (expected 0,0)");
  if (spec.width < 1 || spec.height < 1 || std::uint32_t(spec.width) > kMaxImageSide ||
      std::uint32_t(spec.height) > kMaxImageSide)
    fail(source, "size " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " (expected 1.." +
                     std::to_string(kMaxImageSide) + " per side)");
  const std::uint64_t pixels = std::uint64_t(spec.width) * std::uint64_t(spec.height);
  if (pixels * 4 * views > kMaxImageValues || pixels * std::uint64_t(spec.nchannels) > kMaxImageValues)
    fail(source, std::to_string(views) + " views of " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                     " with " + std::to_string(spec.nchannels) + " channels exceed the limit of " +
                     std::to_string(kMaxImageValues) + " values");
}

// Reads channels `index` of the file into `out` (width * height RGBA), decoding sRGB codes when `srgb`.
void readView(const std::string& source, OIIO::ImageInput& in, const ChannelIndices& index, bool srgb,
              std::span<float> out) {
  const OIIO::ImageSpec& spec = in.spec();
  int first = index[0], last = index[0];
  for (int i : index) {
    if (i == kNoChannel) continue;
    first = std::min(first, i);
    last = std::max(last, i);
  }
  const int count = last - first + 1;
  std::vector<float> pixels(std::size_t(spec.width) * spec.height * std::size_t(count));
  if (!in.read_image(0, 0, first, last + 1, OIIO::TypeDesc::FLOAT, pixels.data()))
    fail(source, "read: " + oiioDetail(in.geterror()));
  for (std::size_t p = 0; p < out.size() / 4; ++p) {
    const float* src = &pixels[p * std::size_t(count)];
    for (int c = 0; c < 3; ++c) {
      const float v = src[index[c] - first];
      out[4 * p + c] = srgb ? gpu_shared::ht_srgb_decode(v) : v;
    }
    out[4 * p + 3] = index[3] == kNoChannel ? 1.0f : src[index[3] - first];
  }
}

ImageHeader headerOf(const std::string& source, const OIIO::ImageSpec& spec) {
  ImageHeader header;
  header.viewNames = multiViewNames(spec);
  const std::uint64_t views = header.viewNames.empty() ? 1 : header.viewNames.size();
  checkSize(source, spec, views);
  header.width = std::uint32_t(spec.width);
  header.height = std::uint32_t(spec.height);
  header.views = std::uint32_t(views);
  header.channelNames.assign(spec.channelnames.begin(), spec.channelnames.end());
  for (int c = 0; c < spec.nchannels; ++c) header.channelTypes.push_back(sampleTypeOf(spec.channelformat(c)));
  header.attributes = stringAttributes(spec);
  return header;
}

ImageFile readOpen(const std::string& source, OIIO::ImageInput& in) {
  const OIIO::ImageSpec& spec = in.spec();
  ImageFile image;
  static_cast<ImageHeader&>(image) = headerOf(source, spec);
  const SampleType type = sampleTypeOf(spec.format);
  const bool integer = type == SampleType::UInt8 || type == SampleType::UInt16;
  const bool srgb = integer && !OIIO::Strutil::iequals(spec.get_string_attribute("oiio:ColorSpace"), "Linear");
  const std::size_t viewFloats = std::size_t(image.width) * image.height * 4;
  image.rgba.resize(viewFloats * image.views);
  for (std::uint32_t v = 0; v < image.views; ++v) {
    const ChannelIndices index =
        image.viewNames.empty() ? imageChannels(source, spec) : viewChannels(source, spec, image.viewNames[v], v == 0);
    readView(source, in, index, srgb, std::span<float>(image.rgba).subspan(v * viewFloats, viewFloats));
  }
  in.close();
  return image;
}

// Raw stored values, no premultiplication on read (PNG alpha is unassociated).
OIIO::ImageSpec readConfig() {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  return config;
}

std::unique_ptr<OIIO::ImageInput> openFile(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(source, "no such file (expected a PNG or OpenEXR file)");
  const OIIO::ImageSpec config = readConfig();
  auto in = OIIO::ImageInput::open(source, &config);
  if (!in) fail(source, oiioDetail("") + " (expected a PNG or OpenEXR file)");
  return in;
}

}  // namespace

std::string ImageHeader::attribute(const std::string& name) const {
  for (const auto& [key, value] : attributes) {
    if (key == name) return value;
  }
  return "";
}

ImageHeader readImageHeader(const std::filesystem::path& path) {
  return headerOf(path.string(), openFile(path)->spec());
}

ImageFile readImageFile(const std::filesystem::path& path) { return readOpen(path.string(), *openFile(path)); }

ImageFile decodeImage(std::span<const std::uint8_t> bytes, const std::string& fileName) {
  OIIO::Filesystem::IOMemReader proxy(bytes.data(), bytes.size());
  std::string format = std::filesystem::path(fileName).extension().string();  // the bytes are not a file to probe
  if (!format.empty()) format.erase(0, 1);
  auto in = format.empty() ? nullptr : OIIO::ImageInput::create(format);
  if (!in) fail(fileName, "no reader for the name's extension (expected .png or .exr)");
  OIIO::ImageSpec spec;
  const OIIO::ImageSpec config = readConfig();
  if (!in->set_ioproxy(&proxy) || !in->open(fileName, spec, config))
    fail(fileName, oiioDetail(in->geterror()) + " (expected PNG or OpenEXR bytes)");
  return readOpen(fileName, *in);
}

}  // namespace ht::frame_io
