#include "cli/rays_file.h"

#include <bit>
#include <cctype>
#include <charconv>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "common/error.h"
#include "frame_io/atomic_output_file.h"

namespace ht::cli {
namespace {

static_assert(std::endian::native == std::endian::little, "the binary ray/hit formats are little-endian");
static_assert(sizeof(gpu_shared::HtRay) == kRayRecordBytes, "HtRay must match the 32-byte ray record");
static_assert(sizeof(gpu_shared::HtHit) == kHitRecordBytes, "HtHit must match the 16-byte hit record");

constexpr char kRaysMagic[4] = {'H', 'T', 'R', 'Y'};
constexpr char kHitsMagic[4] = {'H', 'T', 'H', 'T'};
constexpr std::uint16_t kKindClosest = 0, kKindAny = 1;

bool isCsv(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".csv";
}

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& where, const std::string& problem) {
  throw IoError(path.string() + ": " + where + (where.empty() ? "" : ": ") + problem);
}

std::string readAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "", "cannot open for reading");
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) fail(path, "", "read error");
  return s.str();
}

// Writes `bytes` to `path` through a temporary file renamed into place.
void writeAll(const std::filesystem::path& path, const std::string& bytes) {
  frame_io::AtomicOutputFile file(path);
  {
    std::ofstream out(file.tempPath(), std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) throw IoError(path.string() + ": write failed");
  }
  file.commit();
}

template <typename T>
void append(std::string& bytes, const T& value) {
  bytes.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

// Checks magic, version and that the file holds exactly `count` records of `recordBytes` after the header:
// a count claim the file cannot back is refused before any allocation.
std::uint64_t checkedCount(const std::filesystem::path& path, const std::string& bytes, const char (&magic)[4],
                           std::uint64_t recordBytes) {
  if (bytes.size() < kRaysHeaderBytes)
    fail(path, "header", "truncated (" + std::to_string(bytes.size()) + " of 16 bytes)");
  if (std::memcmp(bytes.data(), magic, 4) != 0) {
    fail(path, "header", std::string("bad magic, expected \"") + std::string(magic, 4) + "\"");
  }
  std::uint64_t count = 0;
  std::memcpy(&count, bytes.data() + 8, sizeof(count));
  const std::uint64_t payload = bytes.size() - kRaysHeaderBytes;
  if (count > payload / recordBytes || payload != count * recordBytes) {
    fail(path, "header",
         "count " + std::to_string(count) + " does not match the file size (" + std::to_string(payload) +
             " bytes of records = " + std::to_string(payload / recordBytes) + " records of " +
             std::to_string(recordBytes) + " bytes" + (payload % recordBytes ? ", the last one truncated" : "") + ")");
  }
  return count;
}

bool validRay(const gpu_shared::HtRay& r) {
  // NaN/Inf are legal input (they miss, docs/ACCURACY.md); only an inverted or NaN range is flagged.
  return !(r.tmin > r.tmax) && r.tmin == r.tmin && r.tmax == r.tmax;
}

std::vector<gpu_shared::HtRay> readBinaryRays(const std::filesystem::path& path) {
  const std::string bytes = readAll(path);
  const std::uint64_t count = checkedCount(path, bytes, kRaysMagic, kRayRecordBytes);
  std::uint32_t version = 0;
  std::memcpy(&version, bytes.data() + 4, sizeof(version));
  if (version != kRaysFileVersion)
    fail(path, "header", "unsupported version " + std::to_string(version) + " (expected 1)");
  std::vector<gpu_shared::HtRay> rays(count);
  std::memcpy(rays.data(), bytes.data() + kRaysHeaderBytes, count * kRayRecordBytes);
  for (std::uint64_t i = 0; i < count; ++i) {
    if (!validRay(rays[i])) fail(path, "record " + std::to_string(i), "tmin/tmax is NaN or tmin > tmax");
  }
  return rays;
}

// Parses one CSV line of exactly `n` floats.
std::vector<float> parseFloats(const std::filesystem::path& path, std::size_t lineNo, const std::string& line,
                               std::size_t n) {
  std::vector<float> values;
  std::size_t pos = 0;
  while (pos <= line.size()) {
    std::size_t end = line.find(',', pos);
    if (end == std::string::npos) end = line.size();
    std::string field = line.substr(pos, end - pos);
    const auto first = field.find_first_not_of(" \t\r"), last = field.find_last_not_of(" \t\r");
    field = first == std::string::npos ? "" : field.substr(first, last - first + 1);
    float v = 0.0f;
    const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
    if (field.empty() || ec != std::errc() || ptr != field.data() + field.size()) {
      fail(path, "line " + std::to_string(lineNo),
           "field " + std::to_string(values.size() + 1) + " '" + field + "' is not a number");
    }
    values.push_back(v);
    pos = end + 1;
  }
  if (values.size() != n) {
    fail(path, "line " + std::to_string(lineNo),
         "expected " + std::to_string(n) + " comma-separated numbers, got " + std::to_string(values.size()));
  }
  return values;
}

std::vector<gpu_shared::HtRay> readCsvRays(const std::filesystem::path& path) {
  std::istringstream in(readAll(path));
  std::vector<gpu_shared::HtRay> rays;
  std::string line;
  for (std::size_t lineNo = 1; std::getline(in, line); ++lineNo) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    if (lineNo == 1 && std::isalpha(static_cast<unsigned char>(line[first])) && line.compare(first, 3, "nan") != 0 &&
        line.compare(first, 3, "inf") != 0) {
      continue;  // header line
    }
    const auto v = parseFloats(path, lineNo, line, 8);
    gpu_shared::HtRay r{{v[0], v[1], v[2]}, v[3], {v[4], v[5], v[6]}, v[7]};
    if (!validRay(r)) fail(path, "line " + std::to_string(lineNo), "tmin/tmax is NaN or tmin > tmax");
    rays.push_back(r);
  }
  return rays;
}

std::string binaryHeader(const char (&magic)[4], std::uint32_t versionAndKind, std::uint64_t count) {
  std::string bytes(magic, 4);
  append(bytes, versionAndKind);
  append(bytes, count);
  return bytes;
}

std::string csvFloat(float v) {
  char buf[32];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), v);  // shortest round-trip form
  return ec == std::errc() ? std::string(buf, ptr) : std::string("nan");
}

}  // namespace

std::vector<gpu_shared::HtRay> readRaysFile(const std::filesystem::path& path) {
  return isCsv(path) ? readCsvRays(path) : readBinaryRays(path);
}

void writeRaysFile(const std::filesystem::path& path, std::span<const gpu_shared::HtRay> rays) {
  std::string bytes;
  if (isCsv(path)) {
    bytes = "ox,oy,oz,tmin,dx,dy,dz,tmax\n";
    for (const auto& r : rays) {
      const float v[8] = {r.origin.x, r.origin.y, r.origin.z, r.tmin, r.dir.x, r.dir.y, r.dir.z, r.tmax};
      for (int k = 0; k < 8; ++k) bytes += csvFloat(v[k]) + (k < 7 ? "," : "\n");
    }
  } else {
    bytes = binaryHeader(kRaysMagic, kRaysFileVersion, rays.size());
    bytes.append(reinterpret_cast<const char*>(rays.data()), rays.size_bytes());
  }
  writeAll(path, bytes);
}

void writeHitsFile(const std::filesystem::path& path, std::span<const gpu_shared::HtHit> hits) {
  std::string bytes;
  if (isCsv(path)) {
    bytes = "t,triangle,u,v\n";
    for (const auto& h : hits) {
      const std::string tri = h.triId == gpu_shared::HT_MISS ? "-1" : std::to_string(h.triId);
      bytes += csvFloat(h.t) + "," + tri + "," + csvFloat(h.u) + "," + csvFloat(h.v) + "\n";
    }
  } else {
    bytes = binaryHeader(kHitsMagic, kRaysFileVersion | (std::uint32_t(kKindClosest) << 16), hits.size());
    bytes.append(reinterpret_cast<const char*>(hits.data()), hits.size_bytes());
  }
  writeAll(path, bytes);
}

void writeOcclusionFile(const std::filesystem::path& path, std::span<const std::uint32_t> occluded) {
  std::string bytes;
  if (isCsv(path)) {
    bytes = "occluded\n";
    for (std::uint32_t o : occluded) bytes += o ? "1\n" : "0\n";
  } else {
    bytes = binaryHeader(kHitsMagic, kRaysFileVersion | (std::uint32_t(kKindAny) << 16), occluded.size());
    bytes.append(reinterpret_cast<const char*>(occluded.data()), occluded.size_bytes());
  }
  writeAll(path, bytes);
}

std::vector<gpu_shared::HtHit> readHitsFile(const std::filesystem::path& path) {
  const std::string bytes = readAll(path);
  std::uint16_t version = 0, kind = 0;
  if (bytes.size() >= kRaysHeaderBytes) {
    std::memcpy(&version, bytes.data() + 4, sizeof(version));
    std::memcpy(&kind, bytes.data() + 6, sizeof(kind));
    if (kind == kKindAny) fail(path, "header", "an any-hit (occlusion) file, not closest hits");
  }
  const std::uint64_t count = checkedCount(path, bytes, kHitsMagic, kHitRecordBytes);
  if (version != kRaysFileVersion) fail(path, "header", "unsupported version " + std::to_string(version));
  std::vector<gpu_shared::HtHit> hits(count);
  std::memcpy(hits.data(), bytes.data() + kRaysHeaderBytes, count * kHitRecordBytes);
  return hits;
}

}  // namespace ht::cli
