# Robustness targets, included from the Makefile (include mk/robust.mk).
#
#   make check-robust   test_robust at -O0, -O3 -march=native, -ffast-math and with the
#                       scalar kernel (-DSBL_NO_SIMD); test_core and test_robust under
#                       -fsanitize=address,undefined (clang, else gcc); test_core under
#                       valgrind; the fuzz harness built without libFuzzer, replaying the
#                       seed corpus under the sanitizers. A missing tool is skipped with
#                       a message, never a failure.
#   make fuzz           the libFuzzer harness (clang -fsanitize=fuzzer,address,undefined)
#                       for FUZZ_SECONDS (default 60); new inputs go to build/fuzz/corpus,
#                       crashes to build/fuzz/ (crash-*), seeds from tests/fuzz_corpus.
#
# Uses CC (default cc) and the directory build/. Everything it builds is under
# build/robust and build/fuzz.

CC ?= cc
ROBUST_DIR   := build/robust
FUZZ_DIR     := build/fuzz
FUZZ_SECONDS ?= 60
ROBUST_DEPS  := stereoblend.h tests/sbl_test.h tests/test_robust.c
ROBUST_STRICT := -std=c99 -pedantic -Wall -Wextra -Werror
ROBUST_SAN   := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
HAVE_CLANG_ROBUST := $(shell command -v clang 2>/dev/null)
ROBUST_VARIANTS := O0 O3native fastmath scalar $(if $(HAVE_CLANG_ROBUST),clang_fastmath)

# Prints the first compiler that links and runs a program with the sanitizers (or nothing).
SAN_PROBE = for c in clang gcc $(CC); do \
	  command -v $$c >/dev/null 2>&1 || continue; \
	  printf 'int main(void){return 0;}\n' > $(ROBUST_DIR)/san_probe.c; \
	  if $$c $(ROBUST_SAN) $(ROBUST_DIR)/san_probe.c -o $(ROBUST_DIR)/san_probe >/dev/null 2>&1 && \
	     ./$(ROBUST_DIR)/san_probe; then echo $$c; break; fi; \
	done

.PHONY: check-robust robust-variants robust-sanitize robust-valgrind robust-fuzz-replay fuzz

$(ROBUST_DIR)/test_robust_O0: $(ROBUST_DEPS)
	@mkdir -p $(dir $@)
	$(CC) $(ROBUST_STRICT) -O0 -g -Itools tests/test_robust.c -o $@ -lm
$(ROBUST_DIR)/test_robust_O3native: $(ROBUST_DEPS)
	@mkdir -p $(dir $@)
	$(CC) $(ROBUST_STRICT) -O3 -march=native -Itools tests/test_robust.c -o $@ -lm
$(ROBUST_DIR)/test_robust_fastmath: $(ROBUST_DEPS)
	@mkdir -p $(dir $@)
	$(CC) $(ROBUST_STRICT) -O2 -ffast-math -Itools tests/test_robust.c -o $@ -lm
$(ROBUST_DIR)/test_robust_clang_fastmath: $(ROBUST_DEPS)
	@mkdir -p $(dir $@)
	clang $(ROBUST_STRICT) -O3 -march=native -ffast-math -Itools tests/test_robust.c -o $@ -lm
$(ROBUST_DIR)/test_robust_scalar: $(ROBUST_DEPS)
	@mkdir -p $(dir $@)
	$(CC) $(ROBUST_STRICT) -O2 -DSBL_NO_SIMD -Itools tests/test_robust.c -o $@ -lm

robust-variants: $(addprefix $(ROBUST_DIR)/test_robust_,$(ROBUST_VARIANTS))
	@fail=0; for v in $(ROBUST_VARIANTS); do \
	  echo "== test_robust ($$v)"; \
	  ./$(ROBUST_DIR)/test_robust_$$v || { fail=1; echo "!! test_robust ($$v) FAILED"; }; \
	done; test $$fail -eq 0

# Sanitizers: the first compiler that links a trivial program with them.
robust-sanitize:
	@mkdir -p $(ROBUST_DIR); \
	san=$$($(SAN_PROBE)); \
	if [ -z "$$san" ]; then echo "robust-sanitize: no compiler with -fsanitize=address,undefined, skipped"; exit 0; fi; \
	fail=0; for t in test_core test_stereo test_robust test_metrics; do \
	  echo "== $$t under $$san -fsanitize=address,undefined"; \
	  $$san $(ROBUST_STRICT) -O1 -g $(ROBUST_SAN) -Itools tests/$$t.c -o $(ROBUST_DIR)/$$t-asan -lm || { fail=1; continue; }; \
	  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
	    ./$(ROBUST_DIR)/$$t-asan || { fail=1; echo "!! $$t under sanitizers FAILED"; }; \
	done; test $$fail -eq 0

robust-valgrind:
	@mkdir -p $(ROBUST_DIR); \
	if ! command -v valgrind >/dev/null 2>&1; then echo "robust-valgrind: valgrind not installed, skipped"; exit 0; fi; \
	echo "== test_core under valgrind (memcheck)"; \
	$(CC) $(ROBUST_STRICT) -O1 -g -Itools tests/test_core.c -o $(ROBUST_DIR)/test_core-vg -lm && \
	valgrind -q --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite \
	  ./$(ROBUST_DIR)/test_core-vg

# The harness without libFuzzer (its own main), replaying the seeds under the sanitizers
# (or plain, when no compiler has them).
robust-fuzz-replay:
	@mkdir -p $(ROBUST_DIR); \
	san=$$($(SAN_PROBE)); \
	if [ -n "$$san" ]; then flags="$(ROBUST_SAN)"; else san=$(CC); flags=""; fi; \
	echo "== fuzz_sbl corpus replay ($$san $$flags)"; \
	$$san $(ROBUST_STRICT) -DSBL_FUZZ_STANDALONE -O1 -g $$flags tests/fuzz_sbl.c -o $(ROBUST_DIR)/fuzz_sbl_replay -lm || exit 1; \
	if ./$(ROBUST_DIR)/fuzz_sbl_replay tests/fuzz_corpus/* > $(ROBUST_DIR)/fuzz_replay.log 2>&1; then \
	  tail -1 $(ROBUST_DIR)/fuzz_replay.log; \
	else tail -20 $(ROBUST_DIR)/fuzz_replay.log; echo "!! fuzz corpus replay FAILED"; exit 1; fi

check-robust: robust-variants robust-sanitize robust-valgrind robust-fuzz-replay
	@echo "check-robust: all passed"

fuzz:
	@if ! command -v clang >/dev/null 2>&1; then echo "fuzz: clang not installed, skipped"; exit 0; fi; \
	mkdir -p $(FUZZ_DIR)/corpus; \
	printf '#include <stdint.h>\n#include <stddef.h>\nint LLVMFuzzerTestOneInput(const uint8_t *d, size_t n){(void)d;(void)n;return 0;}\n' > $(FUZZ_DIR)/probe.c; \
	if ! clang -fsanitize=fuzzer $(FUZZ_DIR)/probe.c -o $(FUZZ_DIR)/probe >/dev/null 2>&1; then \
	  echo "fuzz: clang cannot link -fsanitize=fuzzer (libclang-rt / compiler-rt missing), skipped"; exit 0; fi; \
	clang -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
	  tests/fuzz_sbl.c -o $(FUZZ_DIR)/fuzz_sbl -lm || exit 1; \
	cd $(FUZZ_DIR) && { ./fuzz_sbl corpus $(CURDIR)/tests/fuzz_corpus -max_total_time=$(FUZZ_SECONDS) \
	  -print_final_stats=1 -artifact_prefix=./ > fuzz.log 2>&1; echo $$? > fuzz.rc; }; \
	grep -a -E '^(#[0-9]+ +DONE|stat::number_of_executed_units|stat::average_exec_per_sec|SUMMARY)' fuzz.log; \
	rc=$$(cat fuzz.rc); if [ "$$rc" != 0 ]; then tail -40 fuzz.log; \
	  echo "!! fuzz: crash or property violation, input saved as $(FUZZ_DIR)/crash-*"; fi; exit $$rc
