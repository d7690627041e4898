/* The implementation of stereoblend.h in a translation unit of its own: `make check`
   compiles it once per configuration and links it into every test of that
   configuration (tests are then compiled with -DSTEREOBLEND_IMPLEMENTATION_DONE).
   Tests that define STEREOBLEND_STATIC or call internal functions build their own.
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
