# Hidden tests (docs/exercises.md), built like tools/make/asof.mk builds the public
# ones: one GoogleTest binary per chapter with tests in $(HIDDEN)/chNN/, linked
# against the code as of chapter ASOF. Use it together with asof.mk:
#
#   make -f tools/make/asof.mk -f tools/make/hidden.mk ASOF=05 [ONLY=05] [HIDDEN=dir] hidden-tests
#   make -s -f tools/make/asof.mk -f tools/make/hidden.mk ASOF=05 list-hidden-tests
#
# HIDDEN (default tests/hidden) may point outside the tree: the validation of a
# student kit runs the solution kit's hidden tests against the student's code.

HIDDEN ?= tests/hidden
HIDDEN_NUMBERS := $(foreach c,$(ASOF_CHAPTERS),$(if $(ONLY),$(filter $(ONLY),$(call \
                    chapter_number,$(c))),$(call chapter_number,$(c))))
HIDDEN_NUMBERS := $(foreach n,$(HIDDEN_NUMBERS),$(if $(wildcard $(HIDDEN)/ch$(n)/*.cpp),$(n)))
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

define hidden_binary
$(DIR)/hidden/ch$(1): $(patsubst $(HIDDEN)/%.cpp,$(DIR)/obj/hidden/%.o,$(wildcard \
                        $(HIDDEN)/ch$(1)/*.cpp)) $(if $(LIB_OBJS),$(LIB))
	@mkdir -p $$(@D)
	$(call say,LD,hidden tests of chapter $(patsubst 0%,%,$(1)) ($(AS_OF)))
	$(Q)$(CXX) $(LDFLAGS) -o $$@ $$^ -lgtest_main -lgtest -pthread
endef
$(foreach n,$(HIDDEN_NUMBERS),$(eval $(call hidden_binary,$(n))))
