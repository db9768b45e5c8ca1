#pragma once
// Whether this test program runs under AddressSanitizer: its shadow memory leaves no room for
// an address-space limit (ulimit -v), so the tests that set one skip there.
namespace illum::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool sanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool sanitized = true;
#else
inline constexpr bool sanitized = false;
#endif
#else
inline constexpr bool sanitized = false;
#endif

}  // namespace illum::test
