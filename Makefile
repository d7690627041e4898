# stereoblend.h - build, test, demo, bench.
#   make          build tests, demo and tools
#   make check    run every test, built with every compiler present (C99 pedantic
#                 -Werror with cc / gcc / clang, and once as C++)
#   make demo     the temporal filter on a built-in synthetic scene: RMSE and ms/frame

CC      ?= cc
CFLAGS_STRICT = -std=c99 -pedantic -Wall -Wextra -Werror
CXXFLAGS_STRICT = -std=c++11 -Wall -Wextra -Werror
OPT     ?= -O2 -g
LDLIBS  = -lm
BUILD   = build

HAVE_GCC   := $(shell command -v gcc 2>/dev/null)
HAVE_CLANG := $(shell command -v clang 2>/dev/null)
HAVE_GXX   := $(shell command -v g++ 2>/dev/null)
HAVE_CLANGXX := $(shell command -v clang++ 2>/dev/null)
CXX_TEST := $(if $(HAVE_GXX),g++,$(if $(HAVE_CLANGXX),clang++,))

# OpenEXR is optional: the header never needs it; the EXR tool and the real-data
# bench are built when pkg-config finds it.
HAVE_EXR := $(shell pkg-config --exists OpenEXR 2>/dev/null && echo 1)
EXR_CFLAGS := $(if $(HAVE_EXR),$(shell pkg-config --cflags OpenEXR),-DSBL_NO_EXR)
EXR_LIBS   := $(if $(HAVE_EXR),$(shell pkg-config --libs OpenEXR),)

TESTS = test_core test_metrics test_stereo test_robust test_paths test_accuracy
SIMD_TESTS = test_core test_stereo test_paths
HEADERS = stereoblend.h tests/sbl_test.h $(wildcard tools/*.h)

# SIMD paths this CPU can run (the tests compare each against the scalar path)
CPU_FLAGS := $(shell grep -m1 '^flags' /proc/cpuinfo 2>/dev/null)
SIMD_VARIANTS = scalar $(if $(filter avx2,$(CPU_FLAGS)),avx2) $(if $(filter avx512f,$(CPU_FLAGS)),avx512)
FLAGS_scalar = -DSBL_NO_SIMD
FLAGS_avx2   = -mavx2 -mfma
FLAGS_avx512 = -mavx512f -mavx2 -mfma

# every (compiler, test) pair: build/<compiler>/<test>; the default SIMD path of each
# compiler is SSE2 on x86-64 (NEON on AArch64); build/simd-<v>/ are the other paths
COMPILERS = cc $(if $(HAVE_GCC),gcc) $(if $(HAVE_CLANG),clang)
TEST_BINS = $(foreach c,$(COMPILERS),$(addprefix $(BUILD)/$(c)/,$(TESTS))) \
            $(if $(CXX_TEST),$(addprefix $(BUILD)/cxx/,$(TESTS))) \
            $(foreach v,$(SIMD_VARIANTS),$(addprefix $(BUILD)/simd-$(v)/,$(SIMD_TESTS))) \
            $(foreach v,default $(filter-out scalar,$(SIMD_VARIANTS)),$(BUILD)/simd-$(v)/test_simd)

.PHONY: all check demo bench bench-quick bench-perf clean tests
all: tests $(BUILD)/demo $(BUILD)/minimal $(BUILD)/sblexr $(BUILD)/bench

tests: $(TEST_BINS)

$(BUILD)/cc/%: tests/%.c $(HEADERS)
	@mkdir -p $(dir $@)
	cc $(CFLAGS_STRICT) $(OPT) -Itools $< -o $@ $(LDLIBS)
$(BUILD)/gcc/%: tests/%.c $(HEADERS)
	@mkdir -p $(dir $@)
	gcc $(CFLAGS_STRICT) $(OPT) -Itools $< -o $@ $(LDLIBS)
$(BUILD)/clang/%: tests/%.c $(HEADERS)
	@mkdir -p $(dir $@)
	clang $(CFLAGS_STRICT) $(OPT) -Itools $< -o $@ $(LDLIBS)
define SIMD_RULE
$(BUILD)/simd-$(1)/%: tests/%.c $(HEADERS)
	@mkdir -p $$(dir $$@)
	$(CC) $(CFLAGS_STRICT) $(OPT) $(FLAGS_$(1)) -Itools $$< -o $$@ $(LDLIBS)
endef
$(foreach v,scalar avx2 avx512,$(eval $(call SIMD_RULE,$(v))))

# SIMD against scalar in one binary: the scalar path in a translation unit of its own
$(BUILD)/simd_scalar_tu.o: tests/simd_scalar_tu.c stereoblend.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) $(OPT) -DSBL_NO_SIMD -c $< -o $@
$(BUILD)/simd-%/test_simd: tests/test_simd.c $(BUILD)/simd_scalar_tu.o $(HEADERS)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) $(OPT) $(FLAGS_$*) -Itools $< $(BUILD)/simd_scalar_tu.o -o $@ $(LDLIBS)
$(BUILD)/simd-default/test_simd: tests/test_simd.c $(BUILD)/simd_scalar_tu.o $(HEADERS)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) $(OPT) -Itools $< $(BUILD)/simd_scalar_tu.o -o $@ $(LDLIBS)
$(BUILD)/cxx/%: tests/%.c $(HEADERS)
	@mkdir -p $(dir $@)
	$(CXX_TEST) -x c++ $(CXXFLAGS_STRICT) $(OPT) -Itools $< -o $@ $(LDLIBS)

include mk/robust.mk

# the unit tests built every way, then the robustness runs (-O0, -O3 -march=native,
# -ffast-math with gcc and clang, scalar; ASan + UBSan; valgrind; fuzz corpus replay)
check: $(TEST_BINS)
	@$(MAKE) --no-print-directory check-robust
	@fail=0; total=0; \
	for t in $(TEST_BINS); do \
	  total=$$((total+1)); echo "== $$t"; \
	  if ! ./$$t; then fail=$$((fail+1)); echo "!! $$t FAILED"; fi; \
	done; \
	echo "test binaries: $$((total-fail)) passed, $$fail failed"; \
	test $$fail -eq 0

RUNNER = bench/sbl_runner.h
DATASET_SRC = tools/sbl_dataset.c tools/sbl_exr.c

$(BUILD)/demo: examples/demo.c $(HEADERS) $(RUNNER)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) -O2 -Itools $< -o $@ $(LDLIBS)

$(BUILD)/minimal: examples/minimal.c stereoblend.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) -O2 $< -o $@ $(LDLIBS)

$(BUILD)/sblexr: examples/sblexr.c $(DATASET_SRC) $(HEADERS) $(RUNNER) tools/sbl_dataset.h tools/sbl_exr.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) -O2 -Itools $(EXR_CFLAGS) $< $(DATASET_SRC) -o $@ $(EXR_LIBS) $(LDLIBS)

$(BUILD)/bench: bench/bench.c $(DATASET_SRC) $(HEADERS) $(RUNNER) tools/sbl_dataset.h tools/sbl_exr.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) -O2 -Itools $(EXR_CFLAGS) $< $(DATASET_SRC) -o $@ $(EXR_LIBS) $(LDLIBS)

demo: $(BUILD)/demo
	./$(BUILD)/demo

# error against time for every method, synthetic scenes and ../shared/data
bench: $(BUILD)/bench
	./$(BUILD)/bench --out bench/out

# with OpenCV present (libopencv-dev), the perf bench also times the same filter composed
# from OpenCV calls (bench/perf_opencv.cpp) in the same run
HAVE_OPENCV := $(shell pkg-config --exists opencv4 2>/dev/null && echo 1)
ifeq ($(HAVE_OPENCV),1)
$(BUILD)/perf_opencv.o: bench/perf_opencv.cpp
	@mkdir -p $(dir $@)
	$(CXX_TEST) -std=c++11 -O2 $(PERF_FLAGS) $(shell pkg-config --cflags opencv4) -c $< -o $@
$(BUILD)/perf: bench/perf.c stereoblend.h $(BUILD)/perf_opencv.o
	@mkdir -p $(dir $@)
	$(CC) -std=c99 -Wall -Wextra -O2 $(PERF_FLAGS) -DSBL_PERF_OPENCV -c $< -o $(BUILD)/perf.o
	$(CXX_TEST) $(BUILD)/perf.o $(BUILD)/perf_opencv.o -o $@ $(shell pkg-config --libs opencv4) -lpthread $(LDLIBS)
else
$(BUILD)/perf: bench/perf.c stereoblend.h
	@mkdir -p $(dir $@)
	$(CC) -std=c99 -Wall -Wextra -O2 $(PERF_FLAGS) $< -o $@ -lpthread $(LDLIBS)
endif

# speed against the memory-bandwidth floor; PERF_FLAGS picks the SIMD path
# (default: -march=native; PERF_FLAGS=-DSBL_NO_SIMD for the scalar path)
PERF_FLAGS ?= -march=native
bench-perf: $(BUILD)/perf
	./$(BUILD)/perf --out bench/out

# the same in under a minute (CI smoke run; never asserts timings)
bench-quick: $(BUILD)/bench
	./$(BUILD)/bench --quick --out bench/out

clean:
	rm -rf $(BUILD)
