# hylo: one entry point.
#   make            build everything that exists (libraries, tools, tests)
#   make test       install missing Debian packages, build, run every test
#   make demo       plan the default scenes with the committed models
#   make bench      run the benchmarks, write build/bench/results.json
#   make casestudies  the paper's case studies into docs/results.{md,json}
#   make deps       install missing Debian packages only
#   make install    install the library, headers, models, messages, tools and
#                   trainer (PREFIX=/usr/local, DESTDIR=; docs/install.md)
#   make uninstall  remove what make install put
#   make clean      remove build/
# Every output goes under build/. Pieces are described in mk/*.mk.

.DEFAULT_GOAL := all
.DELETE_ON_ERROR:
.SUFFIXES:
# Keep intermediate objects so that a second `make` has nothing to do.
.SECONDARY:

include mk/config.mk
include mk/msgs.mk
include mk/onboard.mk
include mk/trainer.mk
include mk/slurm.mk
include mk/bench.mk
include mk/bench_plan.mk
include mk/node.mk
include mk/render.mk
include mk/export.mk
include mk/toymode.mk
include mk/fuzz.mk
include mk/cross.mk
include mk/casestudies.mk
include mk/accuracy.mk
include mk/install.mk
include mk/docs.mk

# Header dependencies of everything compiled so far (-MMD -MP).
-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)

.PHONY: all test install uninstall demo bench deps venv venv-bench venv-report casestudies model-pictures check-deps clean fuzz fuzz-deps fuzz-corpus cross-test cross-deps models update-goldens pictures

all: check-deps $(ALL_TARGETS)

deps:
	@tools/install-deps

# Python clients and tools: PyPI packages in a git-ignored venv.
venv: .venv/.stamp
.venv/.stamp: tools/requirements.txt
	python3 -m venv .venv
	.venv/bin/pip install -q -r tools/requirements.txt
	@touch $@

# Benchmark references from PyPI (CasADi), added to the same venv.
venv-bench: .venv/.bench-stamp
.venv/.bench-stamp: .venv/.stamp tools/requirements-bench.txt
	.venv/bin/pip install -q -r tools/requirements-bench.txt
	@touch $@

check-deps:
	@tools/install-deps --check

# test, demo and bench build on every CPU unless make was given -j.
BUILD_JOBS = $(if $(findstring -j,$(MAKEFLAGS)),,-j$(shell nproc))

# Tests run in the order listed, as many at once as there are CPUs
# (TEST_JOBS=1: one by one); the sanitizer builds run last.
test: deps
	@$(MAKE) --no-print-directory $(BUILD_JOBS) all
	@$(MAKE) --no-print-directory venv || echo "make test: no Python venv (is PyPI reachable?); Python client checks will be skipped"
	@tools/run-tests $(TESTS) $(TESTS_SAN)

# Plans the default scenes through the planner node with the committed models.
demo: deps
	@$(MAKE) --no-print-directory $(BUILD_JOBS) all
	@tools/demo.sh

bench: deps
	@$(MAKE) --no-print-directory $(BUILD_JOBS) all $(BENCH_TARGETS)
	@$(MAKE) --no-print-directory venv-bench || echo "make bench: no CasADi from PyPI; its reference will be left out"
	@mkdir -p $(BUILD)/bench
	@tools/bench/run $(BUILD)

clean:
	rm -rf $(BUILD)
