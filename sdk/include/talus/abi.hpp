// What a compilation records about itself for the plugin ABI check. These
// macros expand in the translation unit that uses them, so a plugin's
// descriptor carries the compiler and flags that built the plugin, not the
// ones that built Talus.
//
// Compared (a mismatch is refused), because each changes what the host and a
// plugin exchange:
//   real                   talus::Real
//   cxx11_abi              _GLIBCXX_USE_CXX11_ABI: layout of std::string and std::list
//   glibcxx_debug          _GLIBCXX_DEBUG: debug containers, other layouts
//   stdlib                 libstdc++ or libc++: different std:: types altogether
//   fast_math              -ffast-math: breaks the non-finite checks the host relies
//                          on, and (GCC < 13) a -ffast-math shared library turns on
//                          flush-to-zero for the whole process when it loads
// Recorded but not compared: the compiler (GCC and Clang share the Itanium ABI
// and libstdc++; the layouts are compared directly instead), -march (changes
// no SDK layout: the SDK exchanges no SIMD types) and _GLIBCXX_ASSERTIONS
// (adds checks, keeps every layout).
#pragma once

#include <cstddef>

#include "talus/config.hpp"

#define TALUS_STRINGIFY_(x) #x
#define TALUS_STRINGIFY(x) TALUS_STRINGIFY_(x)

// Clang defines __GNUC__ too (as 4.2): ask for it first.
#if defined(__clang__)
#define TALUS_COMPILER_ID "Clang " TALUS_STRINGIFY(__clang_major__) "." TALUS_STRINGIFY(__clang_minor__)
#elif defined(__GNUC__)
#define TALUS_COMPILER_ID "GCC " TALUS_STRINGIFY(__GNUC__) "." TALUS_STRINGIFY(__GNUC_MINOR__)
#else
#define TALUS_COMPILER_ID "unknown compiler"
#endif

#if defined(_LIBCPP_VERSION)
#define TALUS_ABI_STDLIB_ "libc++"
#else
#define TALUS_ABI_STDLIB_ "libstdc++"
#endif
#if defined(_GLIBCXX_USE_CXX11_ABI) && !_GLIBCXX_USE_CXX11_ABI
#define TALUS_ABI_CXX11_ "0"
#else
#define TALUS_ABI_CXX11_ "1"
#endif
#if defined(_GLIBCXX_DEBUG)
#define TALUS_ABI_DEBUG_ "1"
#else
#define TALUS_ABI_DEBUG_ "0"
#endif
#if defined(__FAST_MATH__)
#define TALUS_ABI_FAST_MATH_ "1"
#else
#define TALUS_ABI_FAST_MATH_ "0"
#endif

// The compared flags, "key=value" separated by ';'.
#define TALUS_ABI_FLAGS                                                                        \
  "real=double;stdlib=" TALUS_ABI_STDLIB_ ";cxx11_abi=" TALUS_ABI_CXX11_ ";glibcxx_debug=" \
  TALUS_ABI_DEBUG_ ";fast_math=" TALUS_ABI_FAST_MATH_

#if defined(__OPTIMIZE__)
#define TALUS_ABI_OPTIMISED 1
#else
#define TALUS_ABI_OPTIMISED 0
#endif

namespace talus {

static_assert(sizeof(Real) == sizeof(double), "TALUS_ABI_FLAGS says real=double");

// One measured number of the SDK's exchanged types, e.g.
// {"offsetof(ViscosityInputs, pressure)", 8}.
struct AbiField {
  const char* name;
  std::size_t value;
};

// What talus_add_plugin's build of a plugin recorded besides the descriptor's
// plain fields (a generated source compiled into the plugin with its flags and
// include path; see talus/abi_layout.hpp).
struct PluginBuild {
  const char* build_type;  // CMAKE_BUILD_TYPE of the plugin's build ("" when none)
  int optimised;           // __OPTIMIZE__ was defined
  const AbiField* layout;
  std::size_t layout_size;
};

}  // namespace talus
