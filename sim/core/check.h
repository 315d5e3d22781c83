// Invariant checks. A failed check is a bug in pelage, never bad input: input is
// validated where it enters (scene and preset parsing, sim/core/input_error.h) and
// reported as an error the user can act on.
//   * PELAGE_CHECK(cond): always on. For cheap structural invariants, e.g. at
//     construction.
//   * PELAGE_DCHECK(cond): debug builds only; with NDEBUG (Release) the condition is not
//     evaluated, so it costs nothing on hot paths (index bounds, unit directions).
// A failure prints "file:line: check failed: cond" to stderr and aborts, so a debugger or
// a core dump stops at the broken invariant.
#pragma once

#include <cstdio>
#include <cstdlib>

namespace pelage::detail {

[[noreturn]] inline void check_failed(const char *file, int line, const char *condition) {
    std::fprintf(stderr, "%s:%d: check failed: %s\n", file, line, condition);
    std::fflush(stderr);
    std::abort();
}

}  // namespace pelage::detail

#define PELAGE_CHECK(cond)                                             \
    do {                                                               \
        if (!(cond)) [[unlikely]]                                      \
            ::pelage::detail::check_failed(__FILE__, __LINE__, #cond); \
    } while (false)

#ifdef NDEBUG
// sizeof keeps the condition compiled (names stay checked) but never evaluated.
#define PELAGE_DCHECK(cond) static_cast<void>(sizeof(!(cond)))
#else
#define PELAGE_DCHECK(cond) PELAGE_CHECK(cond)
#endif
