# Exercises: a student kit and a solution kit built from the chapters; the
# markup and the kits are described in docs/exercises.md. Included by the
# Makefile, so these run from the repository root:
#
#   make exercises PLAN=course.toml ASSIGNMENT=a1  the kits of one assignment of a
#                       course plan (docs/course.md): its exercises with the
#                       plan's points; later assignments' exercises stay stubs
#   make exercises [CHAPTERS="03 05"]   build/exercises/student/ and solution/,
#                       with lrt-student.tar.gz and lrt-solution.tar.gz, for the
#                       exercises of the chapters given by number (default: all);
#                       fails if the student kit leaks a solution or a hidden test
#   make validate-exercises [CHAPTERS=...]  build the kits, then check that the
#                       solution kit passes every public and hidden test as of
#                       every chapter, and that the student kit compiles, fails
#                       every test of every chosen exercise and passes all others
#   make try-exercises [CHAPTERS=... | PLAN=... ASSIGNMENT=...]  the kits
#                       without their books, then the student kit's own make test
#                       UPTO=last (every test against the kit's whole library):
#                       only the chosen exercises' stubs may fail tests, only a
#                       later assignment's stubs skip them; the solution kit's
#                       chapters and tests must be the book's (make test runs those)
#   make test-hidden [CH=05]  the hidden tests (tests/hidden/chNN/) against the
#                       code as of each chapter, as make test runs the public ones
#   make lint-exercises  the exercise markup and test names (part of make lint)

.PHONY: exercises validate-exercises try-exercises test-hidden lint-exercises

EXERCISES_OUT := $(BUILD)/exercises
# The chapters given by number (CHAPTERS="03 05", CHOSEN_NUMBERS in the
# Makefile), or an assignment of a plan.
KIT_CHOICE := $(if $(PLAN),--plan $(PLAN))$(if $(ASSIGNMENT), --assignment $(ASSIGNMENT)) \
              $(CHOSEN_NUMBERS)
HIDDEN_MAKE = $(MAKE) --no-print-directory -f tools/make/hidden.mk

exercises:
	python3 tools/exercises/kits.py build --out $(EXERCISES_OUT) $(KIT_CHOICE)

try-exercises:
	python3 tools/exercises/kits.py build --no-book --out $(EXERCISES_OUT) $(KIT_CHOICE)
	python3 tools/exercises/kits.py try --out $(EXERCISES_OUT) UPTO=last

validate-exercises: exercises
	python3 tools/exercises/kits.py validate --out $(EXERCISES_OUT)

lint-exercises:
	python3 tools/exercises/markup.py lint $(CHAPTERS)

test-hidden: $(LINTED)
	@bins=(); \
	for n in $(PREFIXES); do \
	    $(HIDDEN_MAKE) ASOF=$$n ONLY=$(CH) tangle; \
	    $(HIDDEN_MAKE) ASOF=$$n ONLY=$(CH) -j$(JOBS) hidden-tests; \
	    bins+=($$($(HIDDEN_MAKE) -s ASOF=$$n ONLY=$(CH) list-hidden-tests)); \
	done; \
	if [ $${#bins[@]} -eq 0 ]; then echo "test-hidden: no hidden tests"; exit 0; fi; \
	python3 tools/testing/runtests.py "$${bins[@]}"
