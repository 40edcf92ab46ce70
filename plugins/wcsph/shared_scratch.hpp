// Per-particle scratch that two arrays of a rate evaluation take turns in,
// because neither is read while the other is: the fused fluid pass's
// neighbour records (sph/neighbour_records.hpp), and 1/rho for the wall
// passes and pair terms after it. Sharing keeps the larger of the two in
// memory rather than both. Grows only; 64-byte aligned, so a 32-byte record
// never straddles a cache line.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <new>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <typeinfo>

namespace talus::wcsph {

class SharedScratch {
 public:
  static constexpr std::size_t alignment = 64;

  // Room for n objects of T, their lifetimes begun and their values
  // unspecified; what the scratch held before is gone.
  template <class T>
  std::span<T> hold(std::size_t n) {
    static_assert(std::is_trivially_default_constructible_v<T> && std::is_trivially_destructible_v<T>,
                  "the scratch holds trivial types only");
    static_assert(alignof(T) <= alignment);
    // Never empty: the lifetimes begin in real storage even for n = 0.
    const std::size_t bytes = std::max(n * sizeof(T), alignment);
    if (bytes > capacity_) {
      bytes_.reset();
      capacity_ = 0;
      bytes_.reset(static_cast<std::byte*>(::operator new(bytes, std::align_val_t{alignment})));
      capacity_ = bytes;
    }
    T* first = ::new (static_cast<void*>(bytes_.get())) T[n];  // default-initialised: no code
    held_ = &typeid(T);
    count_ = n;
    return {first, n};
  }

  // What the last hold<T>() gave; a logic_error if the scratch holds another type now.
  template <class T>
  std::span<T> held() const {
    if (!held_ || *held_ != typeid(T))
      throw std::logic_error("shared scratch: read as a type it does not hold (an evaluation's passes out of order)");
    return {std::launder(reinterpret_cast<T*>(bytes_.get())), count_};
  }

 private:
  struct AlignedDelete {
    void operator()(std::byte* p) const { ::operator delete(p, std::align_val_t{alignment}); }
  };
  std::unique_ptr<std::byte, AlignedDelete> bytes_;
  std::size_t capacity_ = 0;
  const std::type_info* held_ = nullptr;
  std::size_t count_ = 0;
};

}  // namespace talus::wcsph
