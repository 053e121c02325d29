"""How C++ is compiled, the same for the build, the grader and an IDE
(compile_commands.json), and the precompiled header of the tests."""
