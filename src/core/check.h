#pragma once
// Invariant checks that fire in every build type (they do not depend on NDEBUG). A failed check
// is a bug in radrecon, never a user's mistake: input that can break a condition is refused
// with a UserError (error.h) or a returned failure (result.h) before it gets here.
//
//   RR_CHECK(cond, msg)        the condition and a message
//   RR_CHECK_EQ(a, b, msg)     and _NE, _LT, _LE, _GT, _GE: both operands are printed
//
// The failure paths are out of line and marked cold, so that a check costs the hot loop it
// guards one predictable branch.

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

namespace radrecon::detail {

[[noreturn, gnu::cold, gnu::noinline]] inline void check_failed(const char* file, int line, const char* condition,
                                                                 const char* operands, const char* message) {
  std::fprintf(stderr, "radrecon: internal error at %s:%d: check '%s' failed%s%s: %s\n", file, line, condition,
               operands ? " with " : "", operands ? operands : "", message);
  std::abort();
}

template <typename A, typename B>
[[noreturn, gnu::cold, gnu::noinline]] void check_op_failed(const char* file, int line, const char* condition,
                                                            const char* a_text, const A& a, const char* b_text,
                                                            const B& b, const char* message) {
  std::ostringstream out;
  out.precision(17);
  out << a_text << " = " << a << ", " << b_text << " = " << b;
  check_failed(file, line, condition, out.str().c_str(), message);
}

}  // namespace radrecon::detail

#define RR_CHECK(cond, msg)                                                                   \
  do {                                                                                        \
    if (!(cond)) [[unlikely]]                                                                 \
      ::radrecon::detail::check_failed(__FILE__, __LINE__, #cond, nullptr, msg);              \
  } while (0)

#define RR_CHECK_OP(a, op, b, msg)                                                                         \
  do {                                                                                                     \
    const auto& rr_check_a = (a);                                                                          \
    const auto& rr_check_b = (b);                                                                          \
    if (!(rr_check_a op rr_check_b)) [[unlikely]]                                                          \
      ::radrecon::detail::check_op_failed(__FILE__, __LINE__, #a " " #op " " #b, #a, rr_check_a, #b,       \
                                          rr_check_b, msg);                                                \
  } while (0)

#define RR_CHECK_EQ(a, b, msg) RR_CHECK_OP(a, ==, b, msg)
#define RR_CHECK_NE(a, b, msg) RR_CHECK_OP(a, !=, b, msg)
#define RR_CHECK_LT(a, b, msg) RR_CHECK_OP(a, <, b, msg)
#define RR_CHECK_LE(a, b, msg) RR_CHECK_OP(a, <=, b, msg)
#define RR_CHECK_GT(a, b, msg) RR_CHECK_OP(a, >, b, msg)
#define RR_CHECK_GE(a, b, msg) RR_CHECK_OP(a, >=, b, msg)
