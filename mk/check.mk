# `make check`: every test in every configuration that can catch something distinct,
# built once, run quietly. Included from the Makefile, which defines TESTS (a plain list:
# append new test files there), CFLAGS_STRICT, CXXFLAGS_STRICT, OPT, LDLIBS, BUILD.
#
# A configuration is a compiler, its flags and the tests it runs. Each compiles the
# implementation once (tests/sbl_impl.c -> build/<config>/stereoblend.o; six of them are
# the objects of strict compiles, mk/strict.mk) and links it into all its tests, which
# are compiled with -DSTEREOBLEND_IMPLEMENTATION_DONE (so a test must include what it
# uses, not count on the implementation's includes). The tests of internal sbl__
# functions (INTERNAL_TESTS) are compiled into that object (tests/sbl_impl.c with
# -DSBL_TEST_INTERNAL, their main renamed) and get tests/internal_main.c as main;
# test_simd links it too, with the scalar path in a second object
# (tests/simd_scalar_tu.c).
#
#   gcc             C99 pedantic -Werror, $(OPT), default SIMD path (SSE2 / NEON); + test_simd
#   clang           the same with clang
#   cxx             the same as C++ (g++, else clang++), but test_paths and test_tiles
#   scalar          -DSBL_NO_SIMD (the reference path; no test_tiles: no row gather)
#   avx2, avx512    each SIMD path the CPU can run; + test_simd (against the scalar path)
#   O0              test_robust at -O0 (-O3 is clang-fastmath's; a gcc -O3 -march=native
#                   configuration cost 25 CPU-s of check for IEEE code that -O2 runs on
#                   the same paths: `make check-robust CHECK_O3=1` adds it back)
#   fastmath        test_robust, test_paths with gcc -ffast-math (FTZ/DAZ set by crtfastmath.o)
#   clang-fastmath  test_robust with clang -O3 -march=native -ffast-math
#   asan            every test under -fsanitize=address,undefined at -O0, with SBL_SHORTCUTS 31
#                   (the far tiles, off by default, on) (clang, else gcc;
#                   -O0: a third of the compile time of -O1, and nothing optimised away), and
#                   the fuzz harness replaying tests/fuzz_corpus
#   valgrind        VALGRIND_TESTS of the gcc configuration under memcheck (no rebuild)
#
# Output: one line per run (PASS/FAIL, label, number of checks), then each failure's full
# output, then "N passed, N failed" alone on the last line. A missing compiler or tool is
# a SKIP line, never a failure. V=1 shows the compiler commands.
#
# Cost (make -j2 check from a clean clone): the implementation is one big translation
# unit (~12 s of gcc -O2, 2/3 of the CPU time of check), so the rule is one
# implementation compile per configuration, six of them shared with the strict compiles,
# and tests that do not differ between configurations are compiled once; the longest
# compiles are started first (CHECK_FIRST) so that neither core idles at the end. The
# cost of each command: make -j2 check SHELL=mk/timed.sh CHECK_TIMES=FILE, then
# sh mk/timed.sh --table FILE.

Q := $(if $(filter 1,$(V)),,@)
CC_GCC := $(if $(HAVE_GCC),gcc,$(CC))
HEADER_TESTS = $(filter-out test_metrics,$(TESTS))
VALGRIND_TESTS ?= test_core test_stereo
# tests of the internal row gather and its tiles: compiled into the implementation object
# (tests/sbl_impl.c includes them under SBL_TEST_INTERNAL: a new test of internal
# functions is added there and here); they run where the code differs (gcc, clang, each
# SIMD path, fastmath, asan), not as C++ (the C++ compile of that code is checked by
# strict/header)
INTERNAL_TESTS = test_paths test_tiles
ROW_GATHER_TESTS = $(INTERNAL_TESTS)
# tests that compile their own copy of the implementation (none; a test that must
# configure the implementation differently from tests/sbl_impl.c would be listed here)
SELF_IMPL_TESTS :=
SAN_FLAGS := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
SAN_ENV := ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
           SBL_TEST_SKIP_LONG=1 # test_robust: its 10,000-frame drift runs are numerics only

# the first compiler that links and runs a program with the sanitizers (probed once, and
# only when a recipe needs it)
SAN_PROBE = mkdir -p $(BUILD); for c in clang gcc $(CC); do \
	  command -v $$c >/dev/null 2>&1 || continue; \
	  printf 'int main(void){return 0;}\n' > $(BUILD)/san_probe.c; \
	  if $$c $(SAN_FLAGS) $(BUILD)/san_probe.c -o $(BUILD)/san_probe >/dev/null 2>&1 && \
	     ./$(BUILD)/san_probe; then echo $$c; break; fi; \
	done
SAN_CC = $(eval SAN_CC := $(shell $(SAN_PROBE)))$(SAN_CC)

# ---- the configurations ------------------------------------------------------------
CHECK_CONFIGS := gcc $(if $(HAVE_CLANG),clang) $(if $(CXX_TEST),cxx) scalar \
                 $(filter-out scalar,$(SIMD_VARIANTS)) O0 $(if $(CHECK_O3),O3native) fastmath \
                 $(if $(HAVE_CLANG),clang-fastmath) asan

CFG_CC_gcc = $(CC_GCC)
CFG_FLAGS_gcc = $(CFLAGS_STRICT) $(OPT)
CFG_TESTS_gcc = $(TESTS) test_simd

CFG_CC_clang = clang
CFG_FLAGS_clang = $(CFLAGS_STRICT) $(OPT)
CFG_TESTS_clang = $(filter-out test_tiles,$(TESTS))  # the tiles: gcc, each SIMD path, asan

CFG_CC_cxx = $(CXX_TEST) -x c++
CFG_FLAGS_cxx = $(CXXFLAGS_STRICT) $(OPT)
CFG_TESTS_cxx = $(filter-out $(ROW_GATHER_TESTS),$(TESTS))

CFG_CC_scalar = $(CC_GCC)
CFG_FLAGS_scalar = $(CFLAGS_STRICT) $(OPT) -DSBL_NO_SIMD
CFG_TESTS_scalar = $(filter-out test_tiles,$(HEADER_TESTS))  # no row gather, no tiles

CFG_CC_avx2 = $(CC_GCC)
CFG_FLAGS_avx2 = $(CFLAGS_STRICT) $(OPT) $(FLAGS_avx2)
CFG_TESTS_avx2 = $(HEADER_TESTS) test_simd

CFG_CC_avx512 = $(CC_GCC)
CFG_FLAGS_avx512 = $(CFLAGS_STRICT) $(OPT) $(FLAGS_avx512)
CFG_TESTS_avx512 = $(HEADER_TESTS) test_simd

CFG_CC_O0 = $(CC_GCC)
CFG_FLAGS_O0 = $(CFLAGS_STRICT) -O0 -g
CFG_TESTS_O0 = test_robust

CFG_CC_O3native = $(CC_GCC)
CFG_FLAGS_O3native = $(CFLAGS_STRICT) -O3 -march=native
CFG_TESTS_O3native = test_robust

CFG_CC_fastmath = $(CC_GCC)
CFG_FLAGS_fastmath = $(CFLAGS_STRICT) -O2 -ffast-math
CFG_TESTS_fastmath = test_robust test_paths  # paths: the row gather's tap decisions
# (not test_tiles nor test_simd: they compare two code paths bit for bit, which -ffast-math
# does not promise: measured 2026-11-23, test_tiles under it, 13 of 2104 checks differ in
# the last bit, e.g. N 26.8638954 both ways, and -0 against 0)

CFG_CC_clang-fastmath = clang
CFG_FLAGS_clang-fastmath = $(CFLAGS_STRICT) -O3 -march=native -ffast-math
CFG_TESTS_clang-fastmath = test_robust

CFG_CC_asan = $(if $(SAN_CC),$(SAN_CC),$(CC_GCC))
# (with the far tiles, the one shortcut off by default, so that its code stays tested)
CFG_FLAGS_asan = $(CFLAGS_STRICT) -O0 -g $(if $(SAN_CC),$(SAN_FLAGS)) -DSBL_SHORTCUTS=31
CFG_TESTS_asan = $(TESTS) fuzz_sbl
CFG_ENV_asan = $(SAN_ENV)
$(BUILD)/asan/fuzz_sbl: EXTRA_FLAGS = -DSBL_FUZZ_STANDALONE
RUN_ARGS_asan/fuzz_sbl = tests/fuzz_corpus/*

# Configurations whose implementation object is the one a strict/header compile
# (mk/strict.mk) builds anyway: same compiler, same code path, -O2; only the warning
# flags differ, and they do not change the code. Saves six compiles of the header.
# (only when OPT is exactly -O2)
STRICT_OBJ_OK := $(if $(filter-out -O2,$(strip $(OPT))),,$(filter -O2,$(strip $(OPT))))
STRICT_OBJ_gcc    = $(if $(STRICT_OBJ_OK),$(if $(HAVE_GCC),$(BUILD)/strict/gcc-default.o))
STRICT_OBJ_scalar = $(if $(STRICT_OBJ_OK),$(if $(HAVE_GCC),$(BUILD)/strict/gcc-scalar.o))
STRICT_OBJ_avx2   = $(if $(STRICT_OBJ_OK),$(if $(HAVE_GCC),$(BUILD)/strict/gcc-avx2.o))
STRICT_OBJ_avx512 = $(if $(STRICT_OBJ_OK),$(if $(HAVE_GCC),$(BUILD)/strict/gcc-avx512.o))
STRICT_OBJ_clang  = $(if $(STRICT_OBJ_OK),$(if $(HAVE_CLANG),$(BUILD)/strict/clang-default.o))
STRICT_OBJ_cxx    = $(if $(STRICT_OBJ_OK),$(if $(filter g++,$(CXX_TEST)),$(BUILD)/strict/gxx-default.o))

# A test's own code is the same in the gcc, scalar, SIMD and O3native configurations:
# their flags differ only by -DSBL_NO_SIMD / -m... / -O3, which select the
# implementation's path and optimisation; the tests preprocess to the same text under
# each (checked with gcc -E), and gcc in ISO C mode does not contract a*b+c. So these
# tests are compiled once (build/gcc/<test>.o) and linked against each of these
# configurations' objects: what differs between them is the object. A test that looks
# at the SIMD macros (PATH_TESTS_RE) is compiled in each configuration instead; one
# whose code depends on other flags (-ffast-math: test_robust's FAST_MATH) is in a
# configuration not listed here. The clang configuration links them too: what it
# checks that the others do not is the implementation compiled by clang (its object);
# the tests' own code is compiled by clang in the asan configuration (clang -O0
# -Werror, when clang links the sanitizers) and in clang-fastmath (test_robust).
SHARED_OBJ_CONFIGS = gcc scalar $(filter-out scalar,$(SIMD_VARIANTS)) O3native \
                     $(if $(HAVE_CLANG),clang)
PATH_TESTS_RE := SBL_NO_SIMD|SBL_SIMD|__AVX|__SSE|__FMA|__ARM_NEON|__aarch64__
PATH_TESTS := $(basename $(notdir $(shell grep -l -E '$(PATH_TESTS_RE)' tests/*.c 2>/dev/null)))
SHARED_TESTS = $(filter-out $(INTERNAL_TESTS) $(SELF_IMPL_TESTS) test_simd $(PATH_TESTS),$(TESTS))
$(addprefix $(BUILD)/gcc/,$(addsuffix .o,$(SHARED_TESTS))): $(BUILD)/gcc/%.o: tests/%.c $(HEADERS)
	@mkdir -p $(@D)
	$(Q)$(CFG_CC_gcc) $(CFG_FLAGS_gcc) -Itools -DSTEREOBLEND_IMPLEMENTATION_DONE -c $< -o $@

# build/<config>/stereoblend.o, and build/<config>/<test> for every test of it
INTERNAL_DEPS = tests/sbl_test.h $(addprefix tests/,$(addsuffix .c,$(INTERNAL_TESTS)))
CFG_INTERNAL = $(if $(filter $(INTERNAL_TESTS),$(CFG_TESTS_$(1))),-DSBL_TEST_INTERNAL)
define CONFIG_RULES
ifeq ($$(STRICT_OBJ_$(1)),)
$(BUILD)/$(1)/stereoblend.o: tests/sbl_impl.c stereoblend.h tests/sbl_test_alloc.h $$(INTERNAL_DEPS)
	@mkdir -p $$(@D)
	$$(Q)$$(CFG_CC_$(1)) $$(CFG_FLAGS_$(1)) $$(call CFG_INTERNAL,$(1)) -Itools -c $$< -o $$@
else
$(BUILD)/$(1)/stereoblend.o: $$(STRICT_OBJ_$(1))
	@mkdir -p $$(@D)
	$$(Q)cp $$< $$@
endif
$(foreach t,$(filter $(SHARED_TESTS),$(CFG_TESTS_$(1))),$(if $(filter $(1),$(SHARED_OBJ_CONFIGS)),$(BUILD)/$(1)/$(t))): $(BUILD)/$(1)/%: $(BUILD)/gcc/%.o $(BUILD)/$(1)/stereoblend.o
	$$(Q)$$(CFG_CC_$(1)) $$< $$(@D)/stereoblend.o -o $$@ $$(LDLIBS)
$(BUILD)/$(1)/%: tests/%.c $(BUILD)/$(1)/stereoblend.o $$(HEADERS)
	@mkdir -p $$(@D)
	$$(Q)$$(CFG_CC_$(1)) $$(CFG_FLAGS_$(1)) $$(EXTRA_FLAGS) -Itools \
	  $$(if $$(filter $$*,$$(SELF_IMPL_TESTS)),$$<,-DSTEREOBLEND_IMPLEMENTATION_DONE $$< -x none $$(@D)/stereoblend.o) \
	  -o $$@ $$(LDLIBS)
$(foreach t,$(filter $(INTERNAL_TESTS),$(CFG_TESTS_$(1))),$(BUILD)/$(1)/$(t)): $(BUILD)/$(1)/%: tests/internal_main.c $(BUILD)/$(1)/stereoblend.o
	@mkdir -p $$(@D)
	$$(Q)$$(CFG_CC_$(1)) $$(CFG_FLAGS_$(1)) -DTST_MAIN=tst_$$*_main $$< -x none $$(@D)/stereoblend.o -o $$@ $$(LDLIBS)
endef
$(foreach c,$(CHECK_CONFIGS),$(eval $(call CONFIG_RULES,$(c))))

# test_simd: this configuration's SIMD path (its object) against the scalar path: the
# scalar configuration's object with its global symbols renamed scalar_<name> (objcopy:
# one compile fewer), else a static copy of the implementation (tests/simd_scalar_tu.c)
HAVE_OBJCOPY := $(shell command -v objcopy 2>/dev/null)
SIMD_SCALAR_OBJS = $(BUILD)/simd_scalar_tu.o $(if $(HAVE_OBJCOPY),$(BUILD)/simd_scalar.o)
ifneq ($(HAVE_OBJCOPY),)
$(BUILD)/simd_scalar.o: $(BUILD)/scalar/stereoblend.o
	$(Q)nm -g --defined-only -P $< | awk '{ print $$1 " scalar_" $$1 }' > $@.syms
	$(Q)objcopy --redefine-syms=$@.syms $< $@
$(BUILD)/simd_scalar_tu.o: tests/simd_scalar_tu.c stereoblend.h
	@mkdir -p $(@D)
	$(Q)$(CC_GCC) $(CFLAGS_STRICT) $(OPT) -DSIMD_SCALAR_RENAMED -c $< -o $@
else
$(BUILD)/simd_scalar_tu.o: tests/simd_scalar_tu.c stereoblend.h
	@mkdir -p $(@D)
	$(Q)$(CC_GCC) $(CFLAGS_STRICT) $(OPT) -DSBL_NO_SIMD -c $< -o $@
endif
define SIMD_TEST_RULE
$(BUILD)/$(1)/test_simd: tests/test_simd.c $(SIMD_SCALAR_OBJS) $(BUILD)/$(1)/stereoblend.o $$(HEADERS)
	@mkdir -p $$(@D)
	$$(Q)$$(CFG_CC_$(1)) $$(CFG_FLAGS_$(1)) -Itools $$< -x none $(SIMD_SCALAR_OBJS) $$(@D)/stereoblend.o -o $$@ $$(LDLIBS)
endef
$(foreach c,$(CHECK_CONFIGS),$(if $(filter test_simd,$(CFG_TESTS_$(c))),$(eval $(call SIMD_TEST_RULE,$(c)))))

CHECK_BINS = $(foreach c,$(CHECK_CONFIGS),$(addprefix $(BUILD)/$(c)/,$(CFG_TESTS_$(c))))

# ---- the runs: build/res/<label>.res, written by mk/run_test.sh -----------------------
RUN_TEST = sh mk/run_test.sh
define RUN_RULE
$(BUILD)/res/$(1)/$(2).res: $(BUILD)/$(1)/$(2) FORCE
	$$(Q)$$(RUN_TEST) $$@ $(1)/$(2) env $$(CFG_ENV_$(1)) ./$$< $$(RUN_ARGS_$(1)/$(2))
endef
$(foreach c,$(CHECK_CONFIGS),$(foreach t,$(CFG_TESTS_$(c)),$(eval $(call RUN_RULE,$(c),$(t)))))

HAVE_VALGRIND := $(shell command -v valgrind 2>/dev/null)
VALGRIND = valgrind -q --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite
define VALGRIND_RULE
$(BUILD)/res/valgrind/$(1).res: $(BUILD)/gcc/$(1) FORCE
	$$(Q)$$(RUN_TEST) $$@ valgrind/$(1) $$(VALGRIND) ./$$<
endef
$(foreach t,$(VALGRIND_TESTS),$(eval $(call VALGRIND_RULE,$(t))))

CHECK_RESULTS = $(foreach c,$(CHECK_CONFIGS),$(foreach t,$(CFG_TESTS_$(c)),$(BUILD)/res/$(c)/$(t).res)) \
                $(if $(HAVE_VALGRIND),$(foreach t,$(VALGRIND_TESTS),$(BUILD)/res/valgrind/$(t).res))
CHECK_SKIPS = $(if $(HAVE_CLANG),,clang:not_installed) $(if $(CXX_TEST),,c++:no_g++_or_clang++) \
              $(if $(HAVE_VALGRIND),,valgrind:not_installed) \
              $(if $(SAN_CC),,sanitizers:no_compiler_links_them,_asan/_built_without)

.PHONY: check check-results check-robust tests FORCE
FORCE:

tests: $(CHECK_BINS)

# -k: a test that does not build is reported (FAIL, did not build) and the others still run
check:
	@rm -rf $(BUILD)/res
	@$(MAKE) -k --no-print-directory check-results || true
	@$(RUN_TEST) --summary "$(CHECK_SKIPS)" $(CHECK_RESULTS)

# the longest compiles first, in the order of their measured CPU time (gcc 12, clang 14):
# with -j2 make starts prerequisites in order, and a long compile started last would
# leave the other core idle at the end
STRICT_FIRST = gcc-avx512 gxx-default gcc-avx2 gcc-default gcc-scalar clang-default
CHECK_FIRST = $(if $(CHECK_O3),$(BUILD)/O3native/stereoblend.o) $(BUILD)/fastmath/stereoblend.o \
              $(foreach c,$(STRICT_FIRST),$(if $(filter $(firstword $(subst -, ,$(c))),$(STRICT_COMPILERS_CHECK)),$(BUILD)/strict/$(c).log)) \
              $(if $(HAVE_CLANG),$(BUILD)/clang-fastmath/stereoblend.o) $(if $(HAVE_OBJCOPY),,$(BUILD)/simd_scalar_tu.o)
STRICT_COMPILERS_CHECK = $(if $(HAVE_GCC),gcc) $(if $(HAVE_CLANG),clang) $(if $(HAVE_GXX),gxx)
# then the longest runs (under the sanitizers and valgrind), so that the last jobs are short
CHECK_LONG_RUNS = $(filter $(BUILD)/res/valgrind/%,$(CHECK_RESULTS)) $(filter $(BUILD)/res/asan/%,$(CHECK_RESULTS))
check-results: $(CHECK_FIRST) $(CHECK_LONG_RUNS) $(CHECK_RESULTS)

# the robustness subset alone (the configurations that exist for it)
ROBUST_RESULTS = $(filter $(BUILD)/res/O0/% $(BUILD)/res/O3native/% $(BUILD)/res/fastmath/% \
                   $(BUILD)/res/clang-fastmath/% $(BUILD)/res/scalar/test_robust.res \
                   $(BUILD)/res/avx2/test_robust.res $(BUILD)/res/avx512/test_robust.res \
                   $(BUILD)/res/asan/% $(BUILD)/res/valgrind/%,$(CHECK_RESULTS))
check-robust:
	@rm -rf $(BUILD)/res
	@$(MAKE) -k --no-print-directory $(ROBUST_RESULTS) || true
	@$(RUN_TEST) --summary "$(CHECK_SKIPS)" $(ROBUST_RESULTS)
