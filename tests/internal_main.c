/* main of the tests of internal functions (test_paths, test_tiles): their code is in the
   configuration's implementation object (tests/sbl_impl.c built with SBL_TEST_INTERNAL);
   `make check` compiles this file with -DTST_MAIN=tst_<test>_main for each. */
int TST_MAIN(void);
int main(void) { return TST_MAIN(); }
