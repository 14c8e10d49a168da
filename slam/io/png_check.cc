#include "slam/io/png_check.h"

#include <cstdint>
#include <cstring>

#include <zlib.h>

namespace viqu::io {
namespace {

constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr size_t kChunkOverhead = 12;  // length, type, CRC (bytes)
// The PNG specification caps a chunk's length at 2^31 - 1 bytes.
constexpr uint32_t kMaxChunkLength = 0x7fffffffu;

uint32_t BigEndian32(const unsigned char* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}

}  // namespace

bool LooksLikePng(const std::string& bytes) {
  return bytes.size() >= sizeof(kSignature) && std::memcmp(bytes.data(), kSignature, sizeof(kSignature)) == 0;
}

std::string PngStructureProblem(const std::string& bytes) {
  if (!LooksLikePng(bytes)) return "no PNG signature";
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  size_t pos = sizeof(kSignature);
  bool first = true;
  while (true) {
    if (bytes.size() - pos < kChunkOverhead) return "truncated: the file ends inside a chunk header (no IEND)";
    const uint32_t length = BigEndian32(data + pos);
    const std::string type(bytes, pos + 4, 4);
    if (length > kMaxChunkLength || bytes.size() - pos - kChunkOverhead < length) {
      return "truncated: chunk " + type + " runs past the end of the file";
    }
    if (first && type != "IHDR") return "the first chunk is " + type + ", not IHDR";
    first = false;
    const uint32_t stored = BigEndian32(data + pos + 8 + length);
    const uint32_t computed =
        static_cast<uint32_t>(crc32(crc32(0L, Z_NULL, 0), data + pos + 4, static_cast<uInt>(4 + length)));
    if (stored != computed) return "chunk " + type + " is damaged (CRC mismatch)";
    pos += kChunkOverhead + length;
    if (type == "IEND") return pos == bytes.size() ? "" : "bytes after IEND";
  }
}

}  // namespace viqu::io
