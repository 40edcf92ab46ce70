// Streaming base64 encoder (RFC 4648, with padding) appending to a string.
// VTK's inline "binary" DataArray is base64 of one stream: the byte-count
// header followed by the data, so both go through the same encoder.
#pragma once

#include <cstddef>
#include <string>

namespace talus::writers {

class Base64Encoder {
 public:
  explicit Base64Encoder(std::string& out) : out_(&out) {}
  void add(const void* data, std::size_t n);
  void finish();  // flushes the last 1-2 bytes with '=' padding

 private:
  void emit(const unsigned char* b);
  std::string* out_;
  unsigned char pending_[3] = {0, 0, 0};
  int npending_ = 0;
};

// Decoder for tests and tools; throws std::invalid_argument on bad input.
std::string base64_decode(std::string_view text);

}  // namespace talus::writers
