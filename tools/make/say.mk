# What the build prints. By default each step is one short line, such as
#   CXX    tests/ch05/test_slab_cases.cpp (as of chapter 5)
# and make V=1 prints every command in full instead. A command's own output,
# its errors and warnings, is printed in full either way. Included by the
# Makefile and by tools/make/asof.mk (and so by every make that builds).

# Q starts a recipe line that the short form does not show.
Q := $(if $(V),,@)
# $(call say,STEP,WHAT): the short line of a step, a recipe line of its own.
say = @$(if $(V),:,printf '%-6s %s\n' '$(1)' '$(2)')
