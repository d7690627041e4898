# `make strict`: the header, declarations and implementation (tests/sbl_impl.c), compiled
# with every warning a strict user project turns on, by gcc and clang as C99 and as C++,
# on every SIMD path (the paths are different code). Prints the warning count of each
# compile (the full text is in build/strict/<compile>.log) and fails if there is any.
# `make check` runs seven of the compiles (below) and fails on any warning.

STRICT_WARN   = -Wall -Wextra -Wpedantic -Wconversion -Wsign-conversion -Wdouble-promotion \
                -Wshadow -Wcast-qual -Wundef
STRICT_C      = -std=c99 $(STRICT_WARN) -Wstrict-prototypes -Wmissing-prototypes
STRICT_CXX    = -std=c++11 $(STRICT_WARN) -Wold-style-cast
STRICT_PATHS  = default scalar avx2 avx512
STRICT_default =
STRICT_scalar  = -DSBL_NO_SIMD
STRICT_avx2    = -mavx2 -mfma
STRICT_avx512  = -mavx512f -mavx2 -mfma

STRICT_CC_gcc       = gcc -x c $(STRICT_C)
STRICT_CC_clang     = clang -x c $(STRICT_C)
STRICT_CC_gxx       = g++ -x c++ $(STRICT_CXX) -Wuseless-cast
STRICT_CC_clangxx   = clang++ -x c++ $(STRICT_CXX)
STRICT_COMPILERS = $(if $(HAVE_GCC),gcc) $(if $(HAVE_CLANG),clang) $(if $(HAVE_GXX),gxx) \
                   $(if $(HAVE_CLANGXX),clangxx)
STRICT_LOGS = $(foreach c,$(STRICT_COMPILERS),$(foreach p,$(STRICT_PATHS),$(BUILD)/strict/$(c)-$(p).log))

# The compiles whose objects are also check's implementation objects (mk/check.mk,
# STRICT_OBJ_*) hold the tests of internal functions too (SBL_TEST_INTERNAL, see
# tests/sbl_impl.c: their code comes after the header and is not checked under these
# flags), so that check's configurations use these objects as they are.
STRICT_INTERNAL_SET = gcc-default gcc-scalar gcc-avx2 gcc-avx512 clang-default
STRICT_INTERNAL = $(if $(filter $(1),$(STRICT_INTERNAL_SET)),-DSBL_TEST_INTERNAL)
# clang's warnings all come from its front end, so the clang compiles whose object no
# configuration links (all but clang-default) run -fsyntax-only: the same warnings, about
# 0.4 s instead of 40 s each (7 of them: CI's time). gcc's compiles stay -O2 (its
# -Wmaybe-uninitialized and the like need the optimiser).
STRICT_SYNTAX_ONLY = $(and $(filter clang clangxx,$(1)),$(if $(filter $(1)-$(2),$(STRICT_INTERNAL_SET)),,1))
define STRICT_RULE
$(BUILD)/strict/$(1)-$(2).log: tests/sbl_impl.c stereoblend.h tests/sbl_test_alloc.h $$(if $$(call STRICT_INTERNAL,$(1)-$(2)),$$(INTERNAL_DEPS))
	@mkdir -p $$(@D)
	@rm -f $$(@:.log=.o); $$(STRICT_CC_$(1)) $$(STRICT_$(2)) $$(call STRICT_INTERNAL,$(1)-$(2)) -O2 $$(if $$(call STRICT_SYNTAX_ONLY,$(1),$(2)),-fsyntax-only,-c -o $$(@:.log=.o)) $$< > $$@ 2>&1 || echo "error: did not compile" >> $$@
endef
$(foreach c,$(STRICT_COMPILERS),$(foreach p,$(STRICT_PATHS),$(eval $(call STRICT_RULE,$(c),$(p)))))

.PHONY: strict
strict: $(STRICT_LOGS)
	@total=0; for f in $(STRICT_LOGS); do \
	  n=$$(grep -c -E '(warning|error):' $$f); total=$$((total + n)); \
	  printf '%-40s %4d warnings\n' "$$f" "$$n"; \
	done; \
	for f in $(STRICT_LOGS); do grep -h -o -E '\[-W[a-z0-9=-]+\]' $$f; done | sort | uniq -c | sort -rn; \
	echo "strict: $$total warnings"; test $$total -eq 0

# the object of a strict compile (a compile that failed left none, the rule above removes
# the previous one: say why)
$(BUILD)/strict/%.o: $(BUILD)/strict/%.log
	@test -f $@ || { cat $<; echo "$@: the strict compile failed"; exit 1; }

# `make check` runs 6 of the 16 compiles (`make strict` runs all, and CI runs it):
# gcc on every path, clang and g++ on the default path. Five of their objects are also
# the implementation objects of check's configurations (mk/check.mk).
STRICT_CHECK_SET = gcc-default gcc-scalar gcc-avx2 gcc-avx512 clang-default gxx-default
STRICT_CHECK_LOGS = $(foreach c,$(filter $(addsuffix -%,$(STRICT_COMPILERS)),$(STRICT_CHECK_SET)),$(BUILD)/strict/$(c).log)
$(BUILD)/res/strict/header.res: $(STRICT_CHECK_LOGS) FORCE
	$(Q)$(RUN_TEST) $@ strict/header sh mk/strict_count.sh $(STRICT_CHECK_LOGS)
check-results: $(BUILD)/res/strict/header.res
CHECK_RESULTS += $(BUILD)/res/strict/header.res
