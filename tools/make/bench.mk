# make bench: the BVH benchmark of Appendix A, bench/bvhbench.cpp, which
# chapters/09-bvh-benchmark.md tangles like the library (roots outside lrt/
# are not part of liblrt.a). It measures one configuration, a compiler and
# its optimization flags:
#
#   make bench                                   g++ -O2 (the default)
#   make bench BENCH_CXXFLAGS=-O3
#   make bench BENCH_CXX=clang++ BENCH_CXXFLAGS="-O3 -march=native"
#
# The rule tangles the code as of the last chapter into the configuration's
# build directory, compiles the library there with that compiler and those
# flags (tools/make/asof.mk, given its CXX and CXXFLAGS), then the benchmark
# against the library and Google Benchmark (Debian's libbenchmark-dev), and
# runs it single-threaded. So the library and the program are measured as
# the configuration builds them, and configurations never overwrite each
# other's files. BENCH_CXXFLAGS replaces only the optimization flags of the
# book's (tools/compile/flags.mk): the language, -ffp-contract=off (which the
# watertight triangle test needs) and the warnings stay. The program records
# the compiler and the flags, and prints them with its table and in its JSON.
#
# Data: if ../shared/bench/gen_bench_data.py is there (the shared generator,
# beside the repository; BENCH_GENERATOR=path names another), it writes the
# meshes and ray files once into $(BUILD)/bench-data; otherwise the program
# generates the same data itself from data/bunny.ply. Results: a table on
# stdout and bvhbench.json in the configuration's build directory.
# BENCH_ARGS passes options, e.g. BENCH_ARGS="--methods sah --passes 9", or
# Google Benchmark's own, e.g. BENCH_ARGS=--benchmark_filter=bunny_L2.
#
# Peers: BENCH_PEERS=embree measures Embree 3 beside lrt in the same run
# (Appendix A's peer section). It needs libembree-dev (tools/deps.sh embree
# installs it as root, or names the apt-get line), compiles the program with
# -DLRT_BENCH_EMBREE and -lembree3 into a binary of its own, bvhbench-embree
# beside bvhbench, and runs that one instead. Embree is the only peer; plain
# make and make bench never need it. BENCH_PEER_DEFINES adds -D options to
# the peer's program and BENCH_EMBREE_BIN names where it goes: for the tests
# only (tests/tools/test_bench.py builds a program with an injected fault).

BENCH_CXX ?= $(CXX)
BENCH_CXXFLAGS ?= $(BOOK_OPT)
BENCH_ARGS ?=
# The default configuration is the library's own (tools/make/asof.mk: $(CXX),
# -O2), so it shares the library's build directory and make compiles the
# library once. Any other gets a directory named after it, with every
# character that is not safe in a file name or a make target (spaces, '=',
# '/', ':') made a '_'. Warnings are errors in the default configuration,
# which make and CI build; in the others they are shown but do not stop the
# measurement (GCC 12 at -O3 -march=native warns of a std::reverse of at
# most 8 bytes as if it wrote 32).
bench_equal = $(and $(findstring $(1),$(2)),$(findstring $(2),$(1)))
BENCH_DEFAULT := $(and $(call bench_equal,$(strip $(BENCH_CXX)),$(CXX)),$(call \
                   bench_equal,$(strip $(BENCH_CXXFLAGS)),$(BOOK_OPT)))
BENCH_CONFIG_NAME := $(shell printf '%s' '$(BENCH_CXX) $(BENCH_CXXFLAGS)' | \
                       tr -c 'A-Za-z0-9.+-' '_')
BENCH_BUILD := $(if $(BENCH_DEFAULT),$(BUILD),$(BUILD)/bench/$(BENCH_CONFIG_NAME))
BENCH_VARIANT := $(if $(filter double,$(FLOAT)),double,float)
BENCH_DIR := $(BENCH_BUILD)/$(BENCH_VARIANT)/asof/$(LAST)
BENCH_BIN := $(BENCH_DIR)/bench/bvhbench
BENCH_PEERS ?=
BENCH_KNOWN_PEERS := embree
BENCH_PEER_DEFINES ?=
BENCH_EMBREE_BIN ?= $(BENCH_DIR)/bench/bvhbench-embree
BENCH_JSON := $(BENCH_BUILD)/bvhbench.json
BENCH_DATA := $(BUILD)/bench-data
BENCH_GENERATOR := ../shared/bench/gen_bench_data.py
# The book's flags (tools/compile/flags.mk) with the configuration's level.
BENCH_ALL_CXXFLAGS := $(patsubst $(BOOK_OPT),$(BENCH_CXXFLAGS),$(filter-out $(if \
                        $(BENCH_DEFAULT),,-Werror),$(BOOK_CXXFLAGS))) \
                      $(if $(filter double,$(FLOAT)),$(DOUBLE_FLAGS))
BENCH_ASOF := $(ASOF) ASOF=$(LAST) BUILD=$(BENCH_BUILD) SANITIZE= \
              CXX='$(BENCH_CXX)' CXXFLAGS='$(BENCH_ALL_CXXFLAGS)'
# The program names its configuration from these two strings.
BENCH_RECORD := -DLRT_BENCH_CXX='"$(BENCH_CXX)"' \
                -DLRT_BENCH_CXXFLAGS='"$(strip $(BENCH_CXXFLAGS))"'

# The chapter that writes the benchmark, if CHAPTERS holds it (a kit of
# earlier chapters does not).
BENCH_CHAPTER := $(shell grep -l '^<<bench/bvhbench.cpp>>=' $(filter %.md,$(CHAPTERS)) /dev/null)

.PHONY: bench bench-build bench-lib bench-compiler bench-peers bench-embree-build
bench-compiler:
	@if ! command -v $(firstword $(BENCH_CXX)) > /dev/null; then \
	    echo "make bench: BENCH_CXX=$(BENCH_CXX): no such compiler" \
	         "(not found in PATH)" >&2; exit 1; fi

# make (the build command) compiles the benchmark too, in the default
# configuration, so that it cannot rot between measurements; only make bench
# runs it. Without the benchmark's chapter there is nothing to compile, and
# make bench says so.
# An unknown peer stops make bench before anything is built.
bench-peers:
	@for p in $(BENCH_PEERS); do \
	    case " $(BENCH_KNOWN_PEERS) " in *" $$p "*) ;; *) \
	        echo "make bench: BENCH_PEERS=$(BENCH_PEERS): unknown peer $$p" \
	             "(known: $(BENCH_KNOWN_PEERS))" >&2; exit 1;; esac; done

ifeq ($(BENCH_CHAPTER),)
bench-build:
	@echo "bench: no chapter of this book writes bench/bvhbench.cpp: nothing to build"
bench-embree-build: bench-build
bench: bench-peers bench-build
	@echo "make bench: the benchmark is Appendix A's; this book ends before it" >&2; exit 1
else
# In the default configuration the benchmark shares the library's build
# directory: it waits for make's own lib, so that make -j does not tangle and
# compile the same files twice at once.
bench-lib: $(LINTED) bench-compiler $(if $(BENCH_DEFAULT),lib)
	$(Q)$(BENCH_ASOF) tangle
	$(Q)$(BENCH_ASOF) -j$(JOBS) lib

# The program, compiled with the configuration's compiler and flags.
# $(1): its file; $(2): extra options before the sources; $(3): after them.
bench_compile = $(BENCH_CXX) $(BENCH_ALL_CXXFLAGS) $(BENCH_RECORD) $(2) \
    -I$(BENCH_DIR)/src $(BENCH_DIR)/src/bench/bvhbench.cpp \
    $(BENCH_DIR)/liblrt.a $(3) -lbenchmark -pthread -o $(1)

bench-build: bench-lib
	@mkdir -p $(dir $(BENCH_BIN))
	$(call say,CXX,bench/bvhbench.cpp ($(BENCH_CXX) $(BENCH_CXXFLAGS)))
	$(Q)$(call bench_compile,$(BENCH_BIN))

bench-embree-build: bench-peers bench-lib
	@tools/deps.sh embree
	@mkdir -p $(dir $(BENCH_EMBREE_BIN))
	$(call say,CXX,bench/bvhbench.cpp with Embree ($(BENCH_CXX) $(BENCH_CXXFLAGS)))
	$(Q)$(call bench_compile,$(BENCH_EMBREE_BIN),-DLRT_BENCH_EMBREE \
	    $(BENCH_PEER_DEFINES),-lembree3)

# With a peer, the program that measures it measures lrt too.
bench: bench-peers $(if $(BENCH_PEERS),bench-embree-build,bench-build) bench-data
	@if [ -n "$(SANITIZE)" ]; then \
	    echo "make bench: measure without SANITIZE" >&2; exit 1; fi
	$(if $(BENCH_PEERS),$(BENCH_EMBREE_BIN),$(BENCH_BIN)) --data $(BENCH_DATA) \
	    --json $(BENCH_JSON) $(BENCH_ARGS)
endif

.PHONY: bench-data bench-path
bench-data:
	@if [ ! -f $(BENCH_DATA)/manifest.json ] && [ -f $(BENCH_GENERATOR) ]; \
	then python3 $(BENCH_GENERATOR) --out $(BENCH_DATA); fi

# The configuration's program and data, for tools/bench/compare.py, which
# runs several configurations in turn.
bench-path:
	@echo $(BENCH_BIN) $(BENCH_DATA)
