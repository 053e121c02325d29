# lrt: one text that is both a book and a C++ library.
#
#   make            tangle, lint, compile the library and the benchmark,
#                   weave build/book.pdf
#   make test       every chapter's tests against the code as of that chapter
#   make test CH=02 chapter 2's tests against the code as of chapter 2
#   make test UPTO=05  chapters 1..5's tests against the code as of chapter 5
#                   (UPTO=last: every test against the whole library)
#   make book       only the PDF
#   make html       the web edition, build/html/ (tools/make/html.mk)
#   make tangle     refresh tangled/, the readable tangle that is committed
#   make lint       check the chapters' noweb/Markdown format
#   make bench      the BVH benchmark of Appendix A (tools/make/bench.mk): table + JSON
#   make figures    render the book's figures into figures/ (tools/make/figures.mk);
#                   make check-figures compares them with the committed ones
#   make exercises  student and solution kits; more in tools/make/exercises.mk
#   make grade SUBMISSION=path [OUT=dir]  grade a student's chapters (tools/make/grade.mk)
#
# Options: FLOAT=double (Float is double), SANITIZE=1 (ASan + UBSan build of
# the tests), CHAPTERS="..." and BUILD=dir to build another set of chapters
# (chapter files; the exercise and grading targets take chapter numbers).

SHELL := /bin/bash
.SHELLFLAGS := -eo pipefail -c
.DEFAULT_GOAL := all

BOOK_CHAPTERS := $(sort $(wildcard chapters/[0-9][0-9]-*.md))
CHAPTERS ?= $(BOOK_CHAPTERS)
# make exercises, validate-exercises, try-exercises, grade, grade-batch and
# gradescope choose chapters by number, given in CHAPTERS too (CHAPTERS="03
# 05", as the README says): those numbers are CHOSEN_NUMBERS, and CHAPTERS
# lists the book's chapter files then, as everywhere else.
CHOSEN_NUMBERS := $(filter-out %.md,$(CHAPTERS))
ifneq ($(CHOSEN_NUMBERS),)
override CHAPTERS := $(BOOK_CHAPTERS)
endif
BUILD ?= build
JOBS ?= $(shell nproc)
chapter_number = $(firstword $(subst -, ,$(notdir $(1))))
NUMBERS := $(foreach c,$(CHAPTERS),$(call chapter_number,$(c)))
LAST := $(lastword $(NUMBERS))
PREFIXES := $(or $(CH),$(subst last,$(LAST),$(UPTO)),$(NUMBERS))
ASOF = $(MAKE) --no-print-directory -f tools/make/asof.mk
export CHAPTERS BUILD FLOAT SANITIZE
include tools/make/say.mk
include tools/compile/flags.mk

.PHONY: all deps lint tangle lib test book clean

all: $(LINTED) tangle lib bench-build compile_commands.json book

deps:
	@tools/deps.sh $(DEPS_SET)

# Every target needs Debian's packages (tools/deps.sh) before its first
# recipe runs a packaged program: noweb, pandoc, TeX, ccache, bubblewrap,
# chromium. GNU make brings the makefiles it includes up to date before it
# builds any goal, and runs their rules even under make -n, so a rule that
# makes an included file runs first, whatever the goals. tools/deps.sh only
# looks for files when nothing is missing (a fraction of a second), so it
# runs on every make: a package removed since the last build is caught too.
# Grading needs fewer packages (a Gradescope image has no TeX); make clean
# and make deps none.
NO_DEPS_GOALS := clean deps
GRADE_GOALS := grade grade-batch gradescope
DEPS_SET := $(if $(filter book-measurements,$(MAKECMDGOALS)),measure,$(if \
              $(filter-out $(GRADE_GOALS),$(or $(MAKECMDGOALS),all)),,grade))
# (MAKE_RESTARTS: make starts again once it has made the file; the check has
# just run.)
ifneq ($(filter-out $(NO_DEPS_GOALS),$(or $(MAKECMDGOALS),all)),)
ifeq ($(MAKE_RESTARTS),)
include $(BUILD)/deps.mk
endif
endif
$(BUILD)/deps.mk: FORCE
	tools/deps.sh $(DEPS_SET)
	@[ -f $@ ] || { mkdir -p $(@D) && echo '# tools/deps.sh found every package' > $@; }

# make lint always checks. What needs the checked chapters depends on a stamp
# instead, which the checks renew only when a chapter, a test or a checker
# changed, or a file was added or removed (the list of inputs, kept by cpif).
LINT_INPUTS := $(CHAPTERS) $(sort $(wildcard tests/ch[0-9][0-9]/* tests/hidden/ch[0-9][0-9]/*))
LINT = python3 tools/noweb/lint.py --book $(CHAPTERS) && \
       python3 tools/exercises/markup.py lint $(CHAPTERS)
# The measured numbers that the chapters print (tools/bench/book_numbers.py):
# checked by make lint and before each edition is woven, not before the code
# is built, so that make book-measurements can measure for a chapter that
# names a number the data does not have yet.
# The file is the one book.md's metadata names (tools/book/measured.lua reads
# it there).
MEASUREMENTS := $(shell sed -n 's/^measurements: *//p' book.md)
LINT_NUMBERS = python3 tools/bench/book_numbers.py --check '$(MEASUREMENTS)' $(CHAPTERS)
LINTED := $(BUILD)/linted.stamp

lint:
	$(LINT)
	$(LINT_NUMBERS)

$(LINTED): $(LINT_INPUTS) $(BUILD)/lint-inputs.list tools/noweb/lint.py tools/exercises/markup.py \
           tools/noweb/chunks.py $(wildcard tools/exercises/*.py)
	$(call say,LINT,the chapters and the names of their exercise tests)
	$(Q)$(LINT)
	@touch $@

.PHONY: FORCE
$(BUILD)/lint-inputs.list: FORCE
	@mkdir -p $(@D)
	@echo $(LINT_INPUTS) | cpif $@

tangle: $(LINTED)
	$(call say,TANGLE,tangled/)
	$(Q)python3 tools/noweb/tangle.py --out tangled $(CHAPTERS)

lib: $(LINTED)
	$(Q)$(ASOF) ASOF=$(LAST) tangle
	$(Q)$(ASOF) ASOF=$(LAST) -j$(JOBS) lib

# The code as of chapter N is the tangle of chapters 1..N; it must compile and
# pass the tests of chapters 1..N, so no chapter leans on a later one. The
# tools' own tests (tests/tools) run with the whole set, once: they do not
# depend on FLOAT or SANITIZE. The appendix (09) is a program, the benchmark,
# whose tests run it from Python.
PYTHON_TESTS_09 := tests/tools/test_bench.py tests/tools/test_measurements.py
test: $(LINTED)
	@if [ -z "$$(find $(BUILD) -path '*/obj/tests' -print -quit)" ]; then \
	    echo "make test: the first build compiles each chapter's tests as of every" \
	         "later chapter, which takes several minutes; later builds compile only" \
	         "what changed"; fi
	@bins=(); \
	for n in $(PREFIXES); do \
	    $(ASOF) ASOF=$$n ONLY=$(CH) tangle; \
	    $(ASOF) ASOF=$$n ONLY=$(CH) -j$(JOBS) tests; \
	    bins+=($$($(ASOF) -s ASOF=$$n ONLY=$(CH) list-tests)); \
	done; \
	python3 tools/testing/runtests.py --jobs $(JOBS) $(if $(FLOAT)$(SANITIZE),,$(if $(CH),$(addprefix \
	    --python-tests ,$(PYTHON_TESTS_$(CH))),--python-tests tests/tools)) "$${bins[@]}"

# (+: a make that runs make, whose jobs it shares; make -n shows what it does.)
compile_commands.json: tangle
	+$(Q)$(ASOF) ASOF=$(LAST) COMPILE_COMMANDS=$@ compile-commands

book: $(BUILD)/book.pdf

$(BUILD)/book.pdf: book.md $(wildcard references.bib) $(CHAPTERS) tools/book/weave.sh tools/book/weave.lua \
                   tools/book/fragments.lua tools/noweb/chunks.py tools/book/exercises.lua \
                   tools/book/edition.lua tools/book/indexes.lua tools/book/latex_text.lua \
                   tools/book/preamble.tex \
                   tools/book/tikz-preamble.tex \
                   tools/book/highlight.theme tools/book/layout_check.py \
                   tools/book/measured.lua tools/bench/book_numbers.py $(wildcard $(MEASUREMENTS)) \
                   $(wildcard figures/*) | $(LINTED)
	$(Q)$(LINT_NUMBERS)
	$(call say,WEAVE,$@ (pandoc then pdflatex until the references settle))
	$(Q)tools/book/weave.sh $(BUILD)/book book.md $(CHAPTERS)
	$(Q)cp $(BUILD)/book/book.pdf $@

clean:
	rm -rf $(BUILD) compile_commands.json

include tools/make/exercises.mk
include tools/make/bench.mk
include tools/make/figures.mk
include tools/make/grade.mk
include tools/make/html.mk
