#include "base64.hpp"

#include <stdexcept>
#include <string_view>

namespace talus::writers {

namespace {
constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
}

void Base64Encoder::emit(const unsigned char* b) {
  const unsigned v = (unsigned(b[0]) << 16) | (unsigned(b[1]) << 8) | unsigned(b[2]);
  const char quad[4] = {kAlphabet[(v >> 18) & 63], kAlphabet[(v >> 12) & 63], kAlphabet[(v >> 6) & 63],
                        kAlphabet[v & 63]};
  out_->append(quad, 4);
}

void Base64Encoder::add(const void* data, std::size_t n) {
  auto* p = static_cast<const unsigned char*>(data);
  while (n > 0 && npending_ > 0 && npending_ < 3) {
    pending_[npending_++] = *p++;
    --n;
    if (npending_ == 3) {
      emit(pending_);
      npending_ = 0;
    }
  }
  // Bulk: encode straight into the grown string (no per-quad append).
  const std::size_t groups = n / 3;
  const std::size_t at = out_->size();
  out_->resize(at + groups * 4);
  char* o = out_->data() + at;
  for (std::size_t g = 0; g < groups; ++g, p += 3, o += 4) {
    const unsigned v = (unsigned(p[0]) << 16) | (unsigned(p[1]) << 8) | unsigned(p[2]);
    o[0] = kAlphabet[(v >> 18) & 63];
    o[1] = kAlphabet[(v >> 12) & 63];
    o[2] = kAlphabet[(v >> 6) & 63];
    o[3] = kAlphabet[v & 63];
  }
  n -= groups * 3;
  for (; n > 0; --n) pending_[npending_++] = *p++;
}

void Base64Encoder::finish() {
  if (npending_ == 0) return;
  unsigned char b[3] = {pending_[0], npending_ > 1 ? pending_[1] : (unsigned char)0, 0};
  const std::size_t at = out_->size();
  emit(b);
  (*out_)[at + 3] = '=';
  if (npending_ == 1) (*out_)[at + 2] = '=';
  npending_ = 0;
}

std::string base64_decode(std::string_view text) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::string out;
  unsigned acc = 0;
  int bits = 0;
  for (char c : text) {
    if (c == '=' || c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
    const int v = value(c);
    if (v < 0) throw std::invalid_argument("base64: invalid character");
    acc = (acc << 6) | unsigned(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<char>((acc >> bits) & 0xff));
    }
  }
  return out;
}

}  // namespace talus::writers
