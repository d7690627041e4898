# stereoblend.h - build, test, demo, bench.
#   make          build tests, demo and tools
#   make check    every test in every configuration (C99 pedantic -Werror with gcc and
#                 clang, C++, scalar and each SIMD path, -O0, -O3 -march=native,
#                 -ffast-math, ASan + UBSan, valgrind, fuzz corpus replay): one line per
#                 run, failures in full, "N passed, N failed" last (mk/check.mk)
#   make strict   the header under -Wconversion, -Wshadow, -Wold-style-cast, ... (mk/strict.mk)
#   make demo     the temporal filter on a built-in synthetic scene: RMSE and ms/frame

CC      ?= cc
CFLAGS_STRICT = -std=c99 -pedantic -Wall -Wextra -Werror
CXXFLAGS_STRICT = -std=c++11 -Wall -Wextra -Werror
OPT     ?= -O2            # the tests' optimisation (OPT='-O2 -g' to debug one)
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

# the unit tests (tests/<name>.c): append new ones here; mk/check.mk builds and runs
# each in every configuration
TESTS = test_core test_metrics test_stereo test_robust test_paths test_engine test_adaptive test_tiles \
        test_accuracy
HEADERS = stereoblend.h tests/sbl_test.h tests/sbl_test_alloc.h $(wildcard tools/*.h)

# SIMD paths this CPU can run (the tests compare each against the scalar path)
CPU_FLAGS := $(shell grep -m1 '^flags' /proc/cpuinfo 2>/dev/null)
SIMD_VARIANTS = scalar $(if $(filter avx2,$(CPU_FLAGS)),avx2) $(if $(filter avx512f,$(CPU_FLAGS)),avx512)
FLAGS_scalar = -DSBL_NO_SIMD
FLAGS_avx2   = -mavx2 -mfma
FLAGS_avx512 = -mavx512f -mavx2 -mfma

.PHONY: all check demo bench bench-quick bench-ceiling ceiling-check bench-perf bench-ipp bench-gather ipp-watch bench-adaptive bench-shortcuts bench-shortcuts-ipp ao clean tests
all: tests $(BUILD)/demo $(BUILD)/minimal $(BUILD)/sblexr $(BUILD)/bench

# make check / make tests / make check-robust: the configurations and the quiet runner
include mk/check.mk
include mk/robust.mk
include mk/strict.mk
include mk/install.mk

RUNNER = bench/sbl_runner.h
DATASET_SRC = tools/sbl_dataset.c tools/sbl_exr.c

$(BUILD)/demo: examples/demo.c $(HEADERS) $(RUNNER)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) -O2 -Itools $< -o $@ $(LDLIBS)

$(BUILD)/minimal: examples/minimal.c stereoblend.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) -O2 -I. $< -o $@ $(LDLIBS)

$(BUILD)/sblexr: examples/sblexr.c $(DATASET_SRC) $(HEADERS) $(RUNNER) tools/sbl_dataset.h tools/sbl_exr.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) -O2 -Itools $(EXR_CFLAGS) $< $(DATASET_SRC) -o $@ $(EXR_LIBS) $(LDLIBS)

$(BUILD)/bench: bench/bench.c $(DATASET_SRC) $(HEADERS) $(RUNNER) tools/sbl_dataset.h tools/sbl_exr.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) -O2 -Itools $(EXR_CFLAGS) $< $(DATASET_SRC) -o $@ $(EXR_LIBS) $(LDLIBS)

$(BUILD)/bench-adaptive: bench/adaptive.c $(DATASET_SRC) $(HEADERS) $(RUNNER) tools/sbl_dataset.h tools/sbl_exr.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) -O2 -Itools $(EXR_CFLAGS) $< $(DATASET_SRC) -o $@ $(EXR_LIBS) $(LDLIBS)

$(BUILD)/adaptive_ipp: bench/adaptive_ipp.c $(DATASET_SRC) $(HEADERS) $(RUNNER) tools/sbl_dataset.h tools/sbl_exr.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) -O2 -g -Itools $(EXR_CFLAGS) $< $(DATASET_SRC) -o $@ $(EXR_LIBS) $(LDLIBS)

# what each adaptive shortcut saves and adds (one library build per shortcut set)
SHORTCUT_MASKS := 31 30 29 27 23 15 0
SHORTCUT_OBJS := $(patsubst %,$(BUILD)/shortcuts/variant_%.o,$(SHORTCUT_MASKS))
$(BUILD)/shortcuts/variant_%.o: bench/shortcuts_variant.c stereoblend.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) -O2 -DSC_MASK=$* -c $< -o $@
$(BUILD)/shortcuts/shortcuts: bench/shortcuts.c $(SHORTCUT_OBJS) $(DATASET_SRC) $(HEADERS) $(RUNNER) tools/sbl_dataset.h tools/sbl_exr.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) -O2 -g -Itools $(EXR_CFLAGS) $< $(SHORTCUT_OBJS) $(DATASET_SRC) -o $@ $(EXR_LIBS) $(LDLIBS)
$(BUILD)/shortcuts/shortcuts-cg: bench/shortcuts.c $(SHORTCUT_OBJS) $(DATASET_SRC) $(HEADERS) $(RUNNER) tools/sbl_dataset.h tools/sbl_exr.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) -O2 -g -DSC_CALLGRIND -Itools $(EXR_CFLAGS) $< $(SHORTCUT_OBJS) $(DATASET_SRC) -o $@ $(EXR_LIBS) $(LDLIBS)
bench-shortcuts: $(BUILD)/shortcuts/shortcuts
	./$(BUILD)/shortcuts/shortcuts
# the same in instructions per pixel (callgrind; no timing noise)
bench-shortcuts-ipp: $(BUILD)/shortcuts/shortcuts-cg
	sh bench/shortcuts_ipp.sh $(BUILD)/shortcuts/shortcuts-cg

# Mono / FSA / adaptive stereo blend: ms, RMSE, eff spp, stereo inconsistency ratio
bench-adaptive: $(BUILD)/bench-adaptive
	./$(BUILD)/bench-adaptive --out bench/out

$(BUILD)/ao_stereo: examples/ao_stereo.c $(DATASET_SRC) $(HEADERS) tools/sbl_dataset.h tools/sbl_exr.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) -O2 -Itools $(EXR_CFLAGS) $< $(DATASET_SRC) -o $@ $(EXR_LIBS) $(LDLIBS)

# Wu's stereo-consistent SSAO (Mono / FSA / Variant 1 / Variant 2) on the consistency mask
ao: $(BUILD)/ao_stereo
	./$(BUILD)/ao_stereo

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

# instructions per pixel (callgrind, inside the public call only) on the SSE2 and the
# AVX2 build: the noise-free speed figure (valgrind cannot run AVX-512 code)
IPP_CASES ?= easy hard tiny static slant
$(BUILD)/ipp-sse2: bench/ipp.c stereoblend.h
	@mkdir -p $(dir $@)
	$(CC) -std=c99 -Wall -Wextra -O2 -g $< -o $@ $(LDLIBS)
$(BUILD)/ipp-avx2: bench/ipp.c stereoblend.h
	@mkdir -p $(dir $@)
	$(CC) -std=c99 -Wall -Wextra -O2 -g -mavx2 -mfma $< -o $@ $(LDLIBS)
bench-ipp: $(BUILD)/ipp-sse2 $(BUILD)/ipp-avx2
	@sh bench/ipp.sh $(BUILD)/ipp-sse2 $(BUILD)/ipp-avx2 -- $(IPP_CASES)
# where they go, by header function (inlined code charged to its function):
#   python3 bench/ipp_breakdown.py build/ipp-avx2 easy sbl_temporal_filter

# hardware gathers against per-lane loads + transpose on this CPU (why the lane paths
# load scattered taps lane by lane); x86-64 only, AVX2 and AVX-512 by runtime check
$(BUILD)/gather_mb: bench/gather_mb.c
	@mkdir -p $(dir $@)
	$(CC) -std=c99 -Wall -Wextra -O2 $< -o $@
bench-gather: $(BUILD)/gather_mb
	./$(BUILD)/gather_mb

# CI's speed watch: the SSE2 figures against bench/ipp_budget.txt (fails above budget)
ipp-watch: $(BUILD)/ipp-sse2
	@sh bench/ipp_watch.sh $(BUILD)/ipp-sse2

# the same in under a minute (CI smoke run; never asserts timings)
bench-quick: $(BUILD)/bench
	./$(BUILD)/bench --quick --out bench/out

# the statistics oracle (bench/ceiling.c, docs/ESTIMATORS.md 6): what exact per-pixel
# statistics reach against the oracle and the defaults. `make bench-ceiling`: every
# synthetic scene (about 30 minutes); `make ceiling-check`: its self-check (CI)
$(BUILD)/ceiling: bench/ceiling.c $(HEADERS) $(RUNNER)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_STRICT) -O2 -Ibench -Itools $< -o $@ $(LDLIBS)

bench-ceiling: $(BUILD)/ceiling
	./$(BUILD)/ceiling

ceiling-check: $(BUILD)/ceiling
	./$(BUILD)/ceiling --check --var-spp 256

clean:
	rm -rf $(BUILD)
