# make bench: the BVH benchmark of chapter 6, bench/bvhbench.cpp, which the
# chapter tangles like the library (roots outside lrt/ are not part of
# liblrt.a). The rule builds the library as of the last chapter, compiles
# the benchmark against it and Google Benchmark (Debian's libbenchmark-dev)
# with -O2 and no architecture-specific flags, and runs it single-threaded.
#
# Data: if ../shared/bench/gen_bench_data.py is there (the shared generator,
# beside the repository), it writes the meshes and ray files once into
# $(BUILD)/bench-data; otherwise the program generates the same data itself
# from data/bunny.ply. Results: a table on stdout and $(BUILD)/bvhbench.json.
# BENCH_ARGS passes options, e.g. BENCH_ARGS="--methods sah --passes 9", or
# Google Benchmark's own, e.g. BENCH_ARGS=--benchmark_filter=bunny_L2.

BENCH_VARIANT := $(if $(filter double,$(FLOAT)),double,float)
BENCH_DIR := $(BUILD)/$(BENCH_VARIANT)/asof/$(LAST)
BENCH_BIN := $(BENCH_DIR)/bench/bvhbench
BENCH_DATA := $(BUILD)/bench-data
BENCH_GENERATOR := ../shared/bench/gen_bench_data.py
BENCH_CXXFLAGS := -std=c++17 -O2 -g -ffp-contract=off -Wall -Wextra -Werror \
                  $(if $(filter double,$(FLOAT)),-DLRT_FLOAT_AS_DOUBLE)
BENCH_ARGS ?=

# The chapter that writes the benchmark, if CHAPTERS holds it (a kit of
# earlier chapters does not).
BENCH_CHAPTER := $(shell grep -l '^<<bench/bvhbench.cpp>>=' $(CHAPTERS) /dev/null)

.PHONY: bench bench-build
# make (the build command) compiles the benchmark too, so that it cannot rot
# between measurements; only make bench runs it. Without the benchmark's
# chapter there is nothing to compile, and make bench says so.
ifeq ($(BENCH_CHAPTER),)
bench-build:
	@echo "bench: no chapter of this book writes bench/bvhbench.cpp: nothing to build"
bench: bench-build
	@echo "make bench: the benchmark is chapter 6's; this book ends before it" >&2; exit 1
else
bench-build: lint
	$(ASOF) ASOF=$(LAST) tangle
	$(ASOF) ASOF=$(LAST) -j$(JOBS) lib
	@mkdir -p $(dir $(BENCH_BIN))
	$(CXX) $(BENCH_CXXFLAGS) -I$(BENCH_DIR)/src \
	    $(BENCH_DIR)/src/bench/bvhbench.cpp $(BENCH_DIR)/liblrt.a \
	    -lbenchmark -pthread -o $(BENCH_BIN)

bench: bench-build
	@if [ -n "$(SANITIZE)" ]; then \
	    echo "make bench: measure without SANITIZE" >&2; exit 1; fi
	@if [ ! -f $(BENCH_DATA)/manifest.json ] && [ -f $(BENCH_GENERATOR) ]; \
	then python3 $(BENCH_GENERATOR) --out $(BENCH_DATA); fi
	$(BENCH_BIN) --data $(BENCH_DATA) --json $(BUILD)/bvhbench.json \
	    $(BENCH_ARGS)
endif
