#pragma once
// Invariant checks that fire in every build type (they do not depend on NDEBUG).

#include <cstdio>
#include <cstdlib>

#define RR_CHECK(cond, msg)                                                             \
  do {                                                                                  \
    if (!(cond)) {                                                                      \
      std::fprintf(stderr, "radrecon: internal error at %s:%d: check '%s' failed: %s\n", \
                   __FILE__, __LINE__, #cond, msg);                                     \
      std::abort();                                                                     \
    }                                                                                   \
  } while (0)
