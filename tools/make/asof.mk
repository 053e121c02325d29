# Builds the code as of chapter ASOF: the tangle of the chapters numbered up to
# ASOF (with #line directives, so diagnostics name the chapter and line), the
# library, and one GoogleTest binary per chapter with tests in tests/chNN/.
# Called by the Makefile: first `tangle`, then `lib` or `tests` (a second make,
# so the wildcards below see the freshly tangled files).

SHELL := /bin/bash
.SHELLFLAGS := -eo pipefail -c
include tools/make/say.mk

include tools/compile/flags.mk

VARIANT := $(if $(SANITIZE),sanitize,$(if $(filter double,$(FLOAT)),double,float))
# The flags themselves, and why each is there: tools/compile/flags.mk. Here
# the variant picks among them: SANITIZE=1 builds at -O1 with the sanitizers,
# FLOAT=double adds DOUBLE_FLAGS; the tests replace the library's level and
# debugging information by their own (TEST_OPT, TEST_DEBUG).
OPT := $(if $(SANITIZE),-O1 $(SANITIZERS) -fno-omit-frame-pointer,$(BOOK_OPT))
CXXFLAGS := $(patsubst $(BOOK_OPT),$(OPT),$(BOOK_CXXFLAGS)) \
            $(if $(filter double,$(FLOAT)),$(DOUBLE_FLAGS))
TEST_CXXFLAGS := $(patsubst $(BOOK_DEBUG),$(TEST_DEBUG),$(patsubst \
                   $(BOOK_OPT),$(TEST_OPT),$(CXXFLAGS)))
LDFLAGS := $(if $(SANITIZE),$(SANITIZERS))

chapter_number = $(firstword $(subst -, ,$(notdir $(1))))
up_to_asof = $(shell [ $(call chapter_number,$(1)) -le $(ASOF) ] && echo $(1))
ASOF_CHAPTERS := $(foreach c,$(CHAPTERS),$(call up_to_asof,$(c)))
# $(call tested_numbers,DIR): the chapters with tests in DIR/chNN/ that this
# build tests: chapter ONLY if given, otherwise every chapter up to ASOF.
tested_numbers = $(foreach n,$(foreach c,$(ASOF_CHAPTERS),$(call chapter_number,$(c))), \
                   $(if $(and $(if $(ONLY),$(filter $(ONLY),$(n)),$(n)), \
                              $(wildcard $(1)/ch$(n)/*.cpp)),$(n)))
TEST_NUMBERS := $(strip $(call tested_numbers,tests))

DIR := $(BUILD)/$(VARIANT)/asof/$(ASOF)
# How the short lines name this build: "as of chapter 5", "as of chapter 5,
# double". (A comma in a $(call)'s text would end its argument.)
comma := ,
AS_OF := as of chapter $(patsubst 0%,%,$(ASOF))$(if $(filter-out float,$(VARIANT)),$(comma) $(VARIANT))
SRC := $(DIR)/src
LIB_SRCS := $(shell find $(SRC)/lrt -name '*.cpp' 2>/dev/null | sort)
LIB_OBJS := $(patsubst $(SRC)/%.cpp,$(DIR)/obj/lib/%.o,$(LIB_SRCS))
LIB := $(DIR)/liblrt.a
TEST_BINS := $(foreach n,$(TEST_NUMBERS),$(DIR)/tests/ch$(n))
# The tests' precompiled header (see below).
PCH_DIR := $(BUILD)/$(VARIANT)/pch
PCH := $(PCH_DIR)/test_pch.h.gch
# A test's compile includes the precompiled header's source, whose .gch the
# compiler then reads instead (compile-commands names the header itself).
PCH_INCLUDE := pch/test_pch.h
TEST_FLAGS = -Itests -include $(PCH_INCLUDE) -Winvalid-pch

.PHONY: tangle lib tests list-tests compile-commands

# The tangle is redone only when a chapter or a tool it runs changed (tangle.py
# rewrites only the files whose text changed, so make then recompiles only what
# includes them).
tangle: $(DIR)/tangled.stamp
$(DIR)/tangled.stamp: $(ASOF_CHAPTERS) $(DIR)/chapters.list tools/noweb/tangle.py \
                      tools/noweb/markup_filter.py tools/noweb/fragment_comments.py \
                      tools/exercises/regions.py tools/noweb/chunks.py
	@mkdir -p $(SRC)
	$(call say,TANGLE,$(SRC) (the code $(AS_OF)))
	$(Q)python3 tools/noweb/tangle.py --line-directives --out $(SRC) $(ASOF_CHAPTERS)
	@touch $@

# The list of chapters, rewritten only when it changes (a chapter renamed or
# removed is older than the stamp, yet the tangle must be redone).
.PHONY: FORCE
$(DIR)/chapters.list: FORCE
	@mkdir -p $(@D)
	@echo $(ASOF_CHAPTERS) | cpif $@

# (The empty recipes keep make from saying "Nothing to be done" when all is
# up to date, or when a chapter has no tests.)
lib: $(if $(LIB_OBJS),$(LIB))
	@:

tests: $(TEST_BINS)
	@:

list-tests:
	@$(foreach n,$(TEST_NUMBERS),echo "asof$(ASOF)/ch$(n)=$(DIR)/tests/ch$(n)";)

# compile_commands.json (the Makefile's make), for clangd and IDEs: the
# readable tangle, tangled/, and the tests compiled as this build compiles
# the library and the tests, named from the repository's root
# (tools/compile/compile_commands.py).
COMPILE_COMMANDS ?= compile_commands.json
compile-commands: PCH_INCLUDE := tools/compile/test_pch.h
compile-commands:
	$(call say,GEN,$(COMPILE_COMMANDS))
	$(Q)python3 tools/compile/compile_commands.py --src tangled --cxx '$(CXX)' \
	    --cxxflags '$(CXXFLAGS)' --test-cxxflags '$(TEST_CXXFLAGS)' \
	    --test-flags '$(TEST_FLAGS)' > $(COMPILE_COMMANDS)

$(LIB): $(LIB_OBJS)
	$(call say,AR,liblrt.a ($(AS_OF)))
	$(Q)rm -f $@
	$(Q)ar rcs $@ $^

$(DIR)/obj/lib/%.o: $(SRC)/%.cpp | compile-links
	$(call compile,src/$*.cpp)

$(DIR)/obj/tests/%.o: tests/%.cpp $(PCH) | compile-links
	$(call compile,tests/$*.cpp,$(TEST_FLAGS),$(TEST_CXXFLAGS))

# Every compile runs in $(CC_DIR), where src is a link to the tangle and tests
# one to the test sources, so a translation unit names the same paths
# (src/lrt/..., tests/chNN/..., and the chapters through #line) as of every
# chapter and in every checkout. ccache, where installed, then compiles a test
# once for all the chapters whose code it sees unchanged, and a kit's copy of
# the book's code once for the kit and the book. That is why a test includes
# the headers it uses and never lrt/lrt.h, which every chapter changes: a test
# of chapter 2 is compiled again only as of the chapters that change the
# headers it reads (3 and 5), not as of every later one. CCACHE_NOHASHDIR lets
# it ignore the directory, which the debug information does not record either
# (-fdebug-prefix-map). Diagnostics name tests/... and chapters/..., paths that
# hold from the repository too. The dependency files come out relative to
# $(CC_DIR); sed makes them relative to the repository.
#
# ccache runs in depend mode: it hashes the files the compiler's dependency
# file lists instead of running the preprocessor, so a hit costs a few stats
# and hashes (about 0.04 s, against 0.4 s for a preprocessor-mode hit) and a
# miss does not preprocess twice. -MD rather than -MMD, so that the list, and
# the hash, holds the system headers too (GoogleTest, libstdc++). Direct and
# depend mode refuse headers newer than the compile's start unless told
# include_file_mtime,include_file_ctime: the tangle has just rewritten them,
# and their content, which is what is hashed, is what counts. The list holds
# the precompiled header, about 90 MB: ccache's inode cache keeps a file's
# hash while its inode, size and times stay the same, without which every
# test compile would read and hash it again (a hit would cost 0.5 s).
CC_DIR := $(DIR)/cc
CCACHE := $(shell command -v ccache)
CCACHE_ENV := CCACHE_NOHASHDIR=1 CCACHE_DEPEND=1 CCACHE_INODECACHE=1 \
              CCACHE_SLOPPINESS=include_file_mtime,include_file_ctime,pch_defines,time_macros
# gcc writes the dependency file (-MD) even when the compile fails; the sed
# that makes its paths absolute does not run then, and the next make would
# stop at its relative paths ("No rule to make target src/..."), so a failed
# compile removes it, and the object too: an object of an earlier compile
# without its dependency file would depend on its source alone, and after
# the error was mended in a header the next make would keep it and run the
# old code.
define compile
@mkdir -p $(@D)
$(call say,CXX,$(patsubst src/%,%,$(1)) ($(AS_OF)))
$(Q)cd $(CC_DIR) && $(CCACHE_ENV) $(CCACHE) $(CXX) $(or $(3),$(CXXFLAGS)) \
    -fdebug-prefix-map=$(abspath $(CC_DIR))=. -Isrc $(2) -MD -MP -MT $@ -c $(1) \
    -o $(abspath $@) || { rm -f $(abspath $(basename $@)).d $(abspath $@); exit 1; }
$(Q)sed -i -E 's#(^| )(src|tests|hidden|pch)/#\1$(CC_DIR)/\2/#g' $(basename $@).d
endef

# The test compiles read GoogleTest and the usual standard headers from a
# precompiled header (tools/compile/test_pch.h): parsing GoogleTest once saves 1 to
# 1.5 s of CPU per chapter-5 test file. One per variant, shared by all chapters,
# built with exactly the tests' $(CXX) $(TEST_CXXFLAGS) (remade when they change:
# pch/flags) and in a directory of its own, through ccache too: a kit or a
# second checkout gets a byte-identical file and so hits the tests' cache
# entries. The compiles name it as pch/test_pch.h, a link in $(CC_DIR), so that
# path is the same for every chapter and checkout. -Winvalid-pch (an error
# under -Werror) refuses a precompiled header that does not fit instead of
# quietly parsing the headers again. ccache needs the sloppiness pch_defines,
# time_macros to cache a compile that uses one.

$(PCH_DIR)/test_pch.h: tools/compile/test_pch.h
	@mkdir -p $(@D)
	$(Q)cp $< $@

$(PCH_DIR)/flags: FORCE
	@mkdir -p $(@D)
	@echo $(CXX) $(TEST_CXXFLAGS) | cpif $@

$(PCH): $(PCH_DIR)/test_pch.h $(PCH_DIR)/flags
	$(call say,PCH,tools/compile/test_pch.h (GoogleTest precompiled for the $(VARIANT) tests))
	$(Q)cd $(PCH_DIR) && $(CCACHE_ENV) $(CCACHE) $(CXX) $(TEST_CXXFLAGS) \
	    -fdebug-prefix-map=$(abspath $(PCH_DIR))=. -MD -MP -MT $@ \
	    -x c++-header -c test_pch.h -o test_pch.h.gch
	$(Q)sed -i -E 's#(^| )test_pch\.h#\1$(PCH_DIR)/test_pch.h#g' $(PCH_DIR)/test_pch.h.d

.PHONY: compile-links
compile-links:
	@mkdir -p $(CC_DIR)
	@ln -sfn ../src $(CC_DIR)/src
	@ln -sfn $(abspath tests) $(CC_DIR)/tests
	@ln -sfn $(abspath $(PCH_DIR)) $(CC_DIR)/pch

# $(call test_binary,NN,KIND,SOURCES,WHAT): the GoogleTest binary
# $(DIR)/KIND/chNN of the tests SOURCES/chNN/*.cpp, compiled into
# $(DIR)/obj/KIND/ and linked with the library; WHAT names them in its short
# line. The public tests here, the hidden ones in tools/make/hidden.mk.
define test_binary
$(DIR)/$(2)/ch$(1): $(patsubst $(3)/%.cpp,$(DIR)/obj/$(2)/%.o,$(wildcard \
                      $(3)/ch$(1)/*.cpp)) $(if $(LIB_OBJS),$(LIB))
	@mkdir -p $$(@D)
	$(call say,LD,$(4) of chapter $(patsubst 0%,%,$(1)) ($(AS_OF)))
	$(Q)$(CXX) $(LDFLAGS) -o $$@ $$^ -lgtest_main -lgtest -pthread
endef
$(foreach n,$(TEST_NUMBERS),$(eval $(call test_binary,$(n),tests,tests,tests)))

-include $(shell find $(DIR)/obj -name '*.d' 2>/dev/null) $(wildcard $(PCH_DIR)/*.d)
