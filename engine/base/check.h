// Internal invariant checks. User errors never reach this: they are returned as messages.
#pragma once

#include <cstdio>
#include <cstdlib>

#define VESSELID_CHECK(condition)                                                        \
  do {                                                                                   \
    if (!(condition)) {                                                                  \
      std::fprintf(stderr, "%s:%d: internal invariant failed: %s\n", __FILE__, __LINE__, \
                   #condition);                                                          \
      std::abort();                                                                      \
    }                                                                                    \
  } while (0)
