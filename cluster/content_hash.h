// content_hash.h - SHA-256 (OpenSSL) of byte sequences, as lower-case hex: the digests of the start-up check.
#pragma once
#include <cstdint>
#include <span>
#include <string>

namespace ht::cluster {

class ContentHash {
 public:
  ContentHash();
  ~ContentHash();
  ContentHash(const ContentHash&) = delete;
  ContentHash& operator=(const ContentHash&) = delete;

  ContentHash& add(std::span<const std::uint8_t> bytes);
  ContentHash& add(const std::string& text);  // its length, then its characters
  template <typename T>
  ContentHash& addValue(const T& value) {
    return add(std::span(reinterpret_cast<const std::uint8_t*>(&value), sizeof(T)));
  }
  std::string hex();  // 64 hex digits; ends the hash

 private:
  void* context_;
};

}  // namespace ht::cluster
