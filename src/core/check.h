#pragma once
// Invariant checks that fire in every build type (they do not depend on NDEBUG). A failed check
// is a bug in radrecon, never a user's mistake: input that can break a condition is refused
// with a UserError (error.h) or a returned failure (result.h) before it gets here.
//
//   RR_CHECK(cond, msg)        the condition and a message
//   RR_CHECK_EQ(a, b, msg)     and _NE, _LT, _LE, _GT, _GE: both operands are printed

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

namespace radrecon::detail {

[[noreturn]] inline void check_failed(const char* file, int line, const char* condition, const std::string& operands,
                                      const char* message) {
  std::fprintf(stderr, "radrecon: internal error at %s:%d: check '%s' failed%s%s: %s\n", file, line, condition,
               operands.empty() ? "" : " with ", operands.c_str(), message);
  std::abort();
}

template <typename A, typename B>
std::string describe_operands(const char* a_text, const A& a, const char* b_text, const B& b) {
  std::ostringstream out;
  out.precision(17);
  out << a_text << " = " << a << ", " << b_text << " = " << b;
  return out.str();
}

}  // namespace radrecon::detail

#define RR_CHECK(cond, msg)                                                                  \
  do {                                                                                       \
    if (!(cond)) ::radrecon::detail::check_failed(__FILE__, __LINE__, #cond, std::string(), msg); \
  } while (0)

#define RR_CHECK_OP(a, op, b, msg)                                                                  \
  do {                                                                                              \
    const auto& rr_check_a = (a);                                                                   \
    const auto& rr_check_b = (b);                                                                   \
    if (!(rr_check_a op rr_check_b))                                                                \
      ::radrecon::detail::check_failed(__FILE__, __LINE__, #a " " #op " " #b,                      \
                                       ::radrecon::detail::describe_operands(#a, rr_check_a, #b, rr_check_b), msg); \
  } while (0)

#define RR_CHECK_EQ(a, b, msg) RR_CHECK_OP(a, ==, b, msg)
#define RR_CHECK_NE(a, b, msg) RR_CHECK_OP(a, !=, b, msg)
#define RR_CHECK_LT(a, b, msg) RR_CHECK_OP(a, <, b, msg)
#define RR_CHECK_LE(a, b, msg) RR_CHECK_OP(a, <=, b, msg)
#define RR_CHECK_GT(a, b, msg) RR_CHECK_OP(a, >, b, msg)
#define RR_CHECK_GE(a, b, msg) RR_CHECK_OP(a, >=, b, msg)
