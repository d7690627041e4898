/* The implementation of stereoblend.h in a translation unit of its own: `make check`
   compiles it once per configuration and links it into every test of that
   configuration (tests are then compiled with -DSTEREOBLEND_IMPLEMENTATION_DONE).
   The tests of internal functions are compiled into it (SBL_TEST_INTERNAL, below).
   It is built with allocator hooks that count and can fail (tests/sbl_test_alloc.h),
   so that the *_frame calls' use of SBL_MALLOC / SBL_FREE is tested without a second
   copy of the implementation. */
#include <stdlib.h>
#include "sbl_test_alloc.h"

#ifdef __cplusplus /* `make strict` compiles this file as C++ with -Wold-style-cast */
#define TST_CAST(T, v) static_cast<T>(v)
#else
#define TST_CAST(T, v) ((T)(v))
#endif

static void *tst_malloc(size_t n, void *ctx)
{
    tst_alloc *a = TST_CAST(tst_alloc *, ctx);
    if (a) {
        if (a->fail) return NULL;
        ++a->allocs;
    }
    return malloc(n);
}

static void tst_free(void *p, void *ctx)
{
    tst_alloc *a = TST_CAST(tst_alloc *, ctx);
    if (a && p) ++a->frees;
    free(p);
}

#define SBL_MALLOC(size, ctx) tst_malloc((size), (ctx))
#define SBL_FREE(ptr, ctx) tst_free((ptr), (ctx))
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"

#ifndef __cplusplus
/* the SIMD path of this object, for tests that link it (test_simd prints it) */
const char *tst_simd_name(void);
const char *tst_simd_name(void) { return SBL_SIMD_NAME; }

/* With SBL_TEST_INTERNAL (the C builds of this file in `make check` / `make strict`): the
   tests that call internal sbl__ functions (tests/test_paths.c, tests/test_tiles.c) are
   compiled into this translation unit, after the implementation, with their main
   renamed. They then link against the configuration's one implementation object like
   every other test (tests/internal_main.c is their main) instead of compiling a copy of
   the implementation each (about 10 s of the compiler per test and configuration).
   Their code is checked under the tests' warning flags (make check's -Wall -Wextra
   -pedantic -Werror), not under make strict's, which are for the header: the pragmas
   below apply from here on, after all of the header. */
#ifdef SBL_TEST_INTERNAL
#if defined(__GNUC__) || defined(__clang__)
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wcast-qual"
#pragma GCC diagnostic ignored "-Wstrict-prototypes"
#pragma GCC diagnostic ignored "-Wmissing-prototypes"
#endif
int tst_test_paths_main(void);
int tst_test_tiles_main(void);

#define main tst_test_paths_main
#include "test_paths.c"
#undef main
#undef view
#undef PW
#undef PH
#undef SW
#undef SH

/* static helpers both files define (a test file's macros and static names share one
   translation unit here: a name both define is renamed for the second, its macros are
   undefined after it) */
#define same_float tiles_same_float
#define compiler_contracts tiles_compiler_contracts
#define main tst_test_tiles_main
#include "test_tiles.c"
#undef main
#undef view
#undef same_float
#undef compiler_contracts
#endif /* SBL_TEST_INTERNAL */
#endif /* !__cplusplus */
