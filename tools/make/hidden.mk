# Hidden tests (docs/exercises.md): the build of tools/make/asof.mk, which
# this file includes, and one GoogleTest binary per chapter with tests in
# $(HIDDEN)/chNN/, linked against the code as of chapter ASOF, as asof.mk
# links the public ones:
#
#   make -f tools/make/hidden.mk ASOF=05 [ONLY=05] [HIDDEN=dir] tangle
#   make -f tools/make/hidden.mk ASOF=05 [ONLY=05] [HIDDEN=dir] lib tests hidden-tests
#   make -s -f tools/make/hidden.mk ASOF=05 list-tests list-hidden-tests
#
# HIDDEN (default tests/hidden) may point outside the tree: the validation of a
# student kit runs the solution kit's hidden tests against the student's code.

include tools/make/asof.mk

HIDDEN ?= tests/hidden
HIDDEN_NUMBERS := $(strip $(call tested_numbers,$(HIDDEN)))
HIDDEN_BINS := $(foreach n,$(HIDDEN_NUMBERS),$(DIR)/hidden/ch$(n))

.PHONY: hidden-tests list-hidden-tests

hidden-tests: $(HIDDEN_BINS)
	@:

list-hidden-tests:
	@$(foreach n,$(HIDDEN_NUMBERS),echo "asof$(ASOF)/hidden-ch$(n)=$(DIR)/hidden/ch$(n)";)

$(DIR)/obj/hidden/%.o: $(HIDDEN)/%.cpp $(PCH) | compile-links hidden-link
	$(call compile,hidden/$*.cpp,$(TEST_FLAGS),$(TEST_CXXFLAGS))

# The compile directory's link to the hidden tests (see compile in asof.mk):
# made again on each run, as HIDDEN may name another directory each time.
.PHONY: hidden-link
hidden-link: compile-links
	@ln -sfn $(abspath $(HIDDEN)) $(CC_DIR)/hidden

$(foreach n,$(HIDDEN_NUMBERS),$(eval $(call test_binary,$(n),hidden,$(HIDDEN),hidden tests)))
