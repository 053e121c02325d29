# make figures: the book's rendered figures. Chapter 8 tangles the figure
# program, render/figures.cpp, like the benchmark of Appendix A (roots outside
# lrt/ are not part of liblrt.a). The rule builds the library as of the last
# chapter, always with Float as float (the precision the figures show, whatever
# FLOAT says), compiles the program against it and runs it from the
# repository's root: it writes every rendered figure into figures/ as PNG,
# at the size at which the book prints it (300 pixels per inch or more).
# Then it turns the committed measurements figures/data/bvh-measurements.json
# (see figures/data/README.md) into the table figures/bvh-bench.dat, which
# the book's plot of the BVH benchmark reads with pgfplots when it is woven.
#
# make check-figures: renders every figure again, in memory, and compares it
# with the committed PNG within a tolerance (render/figures.cpp, "Running and
# Checking"), and checks that the committed table is the one the measurements
# give; CI runs it, so that the figures cannot drift from the code or data.
#
# make book-measurements: remeasures figures/data/bvh-measurements.json, the
# one file behind every measured number of chapter 7, Appendix A and the plot
# (tools/bench/measure.py: the bench of Appendix A on the bunny subdivided 0 to
# 4 times, with Embree beside lrt, then callgrind's counts per ray; about ten
# minutes). It needs the shared generator (BENCH_GENERATOR=/path/to/
# gen_bench_data.py if it is not at ../shared/bench/), valgrind and Embree
# (tools/deps.sh measure, which make runs for this goal).
#
# The book itself never renders: it includes the committed files.

FIGURES_DIR := $(BUILD)/float/asof/$(LAST)
FIGURES_BIN := $(FIGURES_DIR)/render/figures
# The flags of the library it links (tools/compile/flags.mk), Float as float.
FIGURES_CXXFLAGS := $(BOOK_CXXFLAGS)
FIGURES_ASOF := $(ASOF) ASOF=$(LAST) FLOAT= SANITIZE=
BENCH_LEVELS_DATA := $(BUILD)/bench-levels

.PHONY: figures figures-build check-figures book-measurements

figures-build: $(LINTED)
	$(Q)$(FIGURES_ASOF) tangle
	$(Q)$(FIGURES_ASOF) -j$(JOBS) lib
	@mkdir -p $(dir $(FIGURES_BIN))
	$(call say,CXX,render/figures.cpp)
	$(Q)$(CXX) $(FIGURES_CXXFLAGS) -I$(FIGURES_DIR)/src \
	    $(FIGURES_DIR)/src/render/figures.cpp $(FIGURES_DIR)/liblrt.a \
	    -o $(FIGURES_BIN)

BENCH_TABLE := figures/bvh-bench.dat

figures: figures-build
	$(FIGURES_BIN) --out figures
	python3 tools/bench/table.py $(MEASUREMENTS) > $(BENCH_TABLE)

check-figures: figures-build
	$(FIGURES_BIN) --check figures
	@python3 tools/bench/table.py $(MEASUREMENTS) | cmp -s - $(BENCH_TABLE) || \
	    { echo "check-figures: $(BENCH_TABLE) is not the table of" \
	           "$(MEASUREMENTS); run make figures and commit it" >&2; exit 1; }
	@echo "$(BENCH_TABLE)      ok: the table of $(MEASUREMENTS)"

book-measurements: bench-embree-build
	python3 $(BENCH_GENERATOR) --out $(BENCH_LEVELS_DATA) --levels 0,1,2,3,4
	python3 tools/bench/measure.py --bench $(BENCH_EMBREE_BIN) --data $(BENCH_LEVELS_DATA) \
	    --out $(MEASUREMENTS)
	python3 tools/bench/table.py $(MEASUREMENTS) > $(BENCH_TABLE)
