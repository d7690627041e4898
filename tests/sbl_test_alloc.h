/* The allocator hooks of the tests' implementation object (tests/sbl_impl.c): SBL_MALLOC
   and SBL_FREE through a context that counts calls and can fail them on request. With
   a NULL context (every call that does not set alloc_context) they are malloc and free. */
#ifndef SBL_TEST_ALLOC_H
#define SBL_TEST_ALLOC_H
typedef struct tst_alloc {
    int fail;   /* 1: the next allocations return NULL                        */
    int allocs; /* successful SBL_MALLOC calls                                */
    int frees;  /* SBL_FREE calls with a non-NULL pointer                     */
} tst_alloc;
#endif
