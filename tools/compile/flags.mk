# The compiler and the flags of every compile of the book's code, defined
# once. Make includes this file (tools/make/asof.mk, which builds the library
# and the tests, and the Makefile, for the benchmark and the figures); Python
# reads it through tools/compile/flags.py (the grader's judge and worker,
# compile_commands.json), without make, which a grading image does not have.
# So it holds only what flags.py reads: comments, and lines NAME := WORDS or
# NAME ?= WORDS, where a word may be $(NAME) of a line above. What depends on
# FLOAT, SANITIZE or a benchmark's configuration is put together from these
# by the makefile that needs it.

# The compiler. make's own default for CXX is g++ too, so this names it for
# Python; an environment's CXX still wins in make, as it always did.
CXX ?= g++

# The language of the book.
CXX_STD := -std=c++17

# -ffp-contract=off: a fused multiply-add would break the exact sign symmetry
# of the watertight triangle test's edge functions (Chapter 3). x86-64 rounds
# every float operation as written, and this forbids the fused multiply-adds
# that would not, so every compile of the book's code, at any optimization
# level (the library, the tests, the benchmark, the grader's judge and
# worker), computes the same results.
FP_FLAGS := -ffp-contract=off

WARNINGS := -Wall -Wextra

# The library and the programs the book builds: -g, so a debugger shows the
# book's code in full, at -O2; warnings are errors, as make and CI build the
# book. The tests, the sanitized build and the benchmark's configurations
# change the level or the debugging information of these flags
# (tools/make/asof.mk, tools/make/bench.mk); FLOAT=double adds DOUBLE_FLAGS.
BOOK_DEBUG := -g
BOOK_OPT := -O2
BOOK_CXXFLAGS := $(CXX_STD) $(BOOK_DEBUG) $(BOOK_OPT) $(FP_FLAGS) $(WARNINGS) -Werror
DOUBLE_FLAGS := -DLRT_FLOAT_AS_DOUBLE

# The tests are compiled at -O1 with GCC's inliner on. A clean make test
# spends far more time compiling tests than running them, and this level
# compiles them in about a quarter less time than -O2
# (tests/ch06/test_bvh.cpp, about 12 against 16 s of CPU) while running them
# nearly as fast. -Og compiles a little faster still (about 10 s) but runs
# chapter 5's tests in 3.1 s against 1.9, which a student waits for on every
# make test CH=05. The library, and the inline code of its headers that a
# test calls, compute the same results at any level (FP_FLAGS). The library
# itself stays at BOOK_OPT.
TEST_OPT := -O1 -finline-functions -finline-small-functions

# -g1 for the tests: line tables and function names, so a crash's backtrace
# and a sanitizer's report still name the test's file and line, but no
# description of local variables and types. Writing those out is over a third
# of a test's compile (tests/ch06/test_bvh.cpp, about 14 against 9 s of CPU)
# and makes its object nearly four times larger. TEST_DEBUG=-g gives the
# tests, and the code they compile from the book's headers, full debugging
# information.
TEST_DEBUG ?= -g1

# SANITIZE=1: the tests built with AddressSanitizer and UndefinedBehavior-
# Sanitizer, at -O1 (tools/make/asof.mk); the first error stops the test.
SANITIZERS := -fsanitize=address,undefined -fno-sanitize-recover=all

# The grader (docs/grading.md). Its judge is the book's code with the public
# and hidden tests, never a student's line, built once per chapter: at -O2 as
# the book's build, and without warnings (-w), which are the book's build's
# business (it makes them errors), not a grade's. The tests index what a
# worker answered: -D_GLIBCXX_ASSERTIONS makes an index past a reply's end an
# abort of the judge (the exercise's tests fail) instead of a read of the
# judge's own memory that a failure message would show the student.
JUDGE_CXXFLAGS := $(CXX_STD) $(BOOK_OPT) $(FP_FLAGS) -w -D_GLIBCXX_ASSERTIONS

# A worker is a student's code, built for each exercise of each submission:
# at -O0, which compiles fastest, with the warnings shown to the student
# but not errors (tools/grading/grade.py --cxxflags replaces these).
WORKER_CXXFLAGS := $(CXX_STD) -O0 $(FP_FLAGS) $(WARNINGS)
