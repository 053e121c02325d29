#!/usr/bin/env python3
"""Write compile_commands.json for the readable tangle, so that clangd and
IDEs index tangled/ and tests/ with the compiler and flags the build uses.

    compile_commands.py --src tangled --cxx CXX --cxxflags FLAGS
                        --test-cxxflags FLAGS --test-flags FLAGS

tools/make/asof.mk runs it (its goal compile-commands) with its own
variables, so a library file's command is the build's compile of it, and a
test's the build's compile of a test, each without what only the build needs
(ccache, the dependency file, the object's path): tests/tools/test_makefile.py
checks that they stay so. Files are named from the repository's root, where
the build names them from a directory of its own (src/ is the tangle there).
"""
import argparse
import glob
import json
import os


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('--src', required=True, help='the tangle: tangled')
    parser.add_argument('--cxx', required=True)
    parser.add_argument('--cxxflags', required=True, help="the library's flags")
    parser.add_argument('--test-cxxflags', required=True, help="the tests' flags")
    parser.add_argument('--test-flags', required=True,
                        help="what a test's compile adds after -I SRC: its includes")
    args = parser.parse_args()
    root = os.getcwd()
    library = sorted(glob.glob(os.path.join(args.src, '**', '*.cpp'), recursive=True))
    tests = sorted(glob.glob('tests/**/*.cpp', recursive=True))
    cxx = args.cxx.split()
    commands = [(f, cxx + args.cxxflags.split() + ['-I' + args.src]) for f in library]
    commands += [(f, cxx + args.test_cxxflags.split() + ['-I' + args.src] +
                  args.test_flags.split()) for f in tests]
    print(json.dumps([{'directory': root, 'file': f, 'arguments': argv + ['-c', f]}
                      for f, argv in commands], indent=1))


if __name__ == '__main__':
    main()
