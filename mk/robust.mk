# Robustness targets, included from the Makefile (include mk/robust.mk).
#
#   make check-robust   the robustness configurations of `make check` alone (mk/check.mk):
#                       test_robust at -O0, -O3 -march=native, -ffast-math (gcc, clang)
#                       and with the scalar kernel (-DSBL_NO_SIMD); every test under
#                       -fsanitize=address,undefined (clang, else gcc); VALGRIND_TESTS
#                       under valgrind; the fuzz harness built without libFuzzer,
#                       replaying the seed corpus under the sanitizers. A missing tool is
#                       skipped with a message, never a failure.
#   make fuzz           the libFuzzer harness (clang -fsanitize=fuzzer,address,undefined)
#                       for FUZZ_SECONDS (default 60); new inputs go to build/fuzz/corpus,
#                       crashes to build/fuzz/ (crash-*), seeds from tests/fuzz_corpus.

FUZZ_DIR     := build/fuzz
FUZZ_SECONDS ?= 60

.PHONY: fuzz
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
