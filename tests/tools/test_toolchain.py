"""Tests of the toolchain itself: the lint's messages, the tangle's line
directives, the weave filter (its cross-check against noweb, footers, code,
examples of fragments, captions, citations) and the check of the woven
book's page layout.

Each broken chapter under lint/ shows one mistake; its test asserts the exact
file:line the lint names, so a message that drifts or points nowhere fails.
"""
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
TOOLS = os.path.join(ROOT, 'tools')
LINT_CASES = os.path.join(HERE, 'lint')

sys.path.insert(0, ROOT)
from tools.book import layout_check  # noqa: E402


def run(cmd, cwd=ROOT):
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)


def lint(*names):
    return run(['python3', os.path.join(TOOLS, 'noweb', 'lint.py')] +
               [os.path.join('tests/tools/lint', name) for name in names])


class LintTest(unittest.TestCase):
    def assertLintError(self, names, where, words):
        result = lint(*names)
        self.assertEqual(result.returncode, 1, result.stderr)
        lines = [l for l in result.stderr.splitlines() if l.startswith('tests/')]
        matching = [l for l in lines if l.startswith('tests/tools/lint/' + where + ': ')]
        self.assertTrue(matching, 'no error at %s in:\n%s' % (where, result.stderr))
        for word in words:
            self.assertIn(word, matching[0])

    def test_good_chapter_passes(self):
        result = lint('good.md')
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(result.stderr, '')

    def test_undefined_fragment_use(self):
        self.assertLintError(['undefined-use.md'], 'undefined-use.md:6',
                             ['undefined fragment', '<<Body of f>>'])

    def test_fragment_never_used(self):
        self.assertLintError(['unused-fragment.md'], 'unused-fragment.md:10',
                             ['<<Helper nobody uses>>', 'never used'])

    def test_unescaped_shift_in_prose(self):
        self.assertLintError(['unescaped-prose.md'], 'unescaped-prose.md:3',
                             ['unescaped <<', '@<<'])

    def test_chunk_without_closing_at(self):
        self.assertLintError(['missing-at.md'], 'missing-at.md:4',
                             ['<<lrt/broken.h>>', 'no closing @', 'line 6'])

    def test_definition_inside_a_chunk_ends_it(self):
        # As noweb reads it: <<Helper>>= starts a chunk, so <<lrt/nested.h>>
        # never meets its @.
        self.assertLintError(['definition-in-chunk.md'], 'definition-in-chunk.md:4',
                             ['<<lrt/nested.h>>', 'never closed by @', 'line 6'])

    def test_tab(self):
        self.assertLintError(['tab.md'], 'tab.md:6', ['tab character'])

    def test_shift_operators_read_as_a_use(self):
        self.assertLintError(['shift-mangled.md'], 'shift-mangled.md:5',
                             ['fragment use', '@<<'])

    def test_root_defined_in_two_chapters(self):
        self.assertLintError(['root-a.md', 'root-b.md'], 'root-a.md:4',
                             ['<<lrt/shared.h>>', 'more than one chapter',
                              'root-b.md'])

    def test_use_of_a_fragment_first_defined_later(self):
        self.assertLintError(['later-definition-a.md', 'later-definition-b.md'],
                             'later-definition-a.md:5',
                             ['later chapter', 'later-definition-b.md:4'])

    def test_reference_to_a_label_of_a_later_chapter(self):
        # A kit of the chapters up to the first could not weave it.
        self.assertLintError(['forward-ref-a.md', 'forward-ref-b.md'],
                             'forward-ref-a.md:3',
                             ['sec:second-tree', 'later chapter',
                              'forward-ref-b.md:3'])
        # References to exercises (tools/book/exercises.lua) too.
        self.assertLintError(['forward-ref-a.md', 'forward-ref-b.md'], 'forward-ref-a.md:5',
                             ['ex:later-problem', 'forward-ref-b.md:7'])
        self.assertLintError(['forward-ref-a.md', 'forward-ref-b.md'], 'forward-ref-a.md:6',
                             ['ex-2.1', 'forward-ref-b.md:9'])
        # The reference back to the first chapter is fine.
        self.assertNotIn('forward-ref-b.md:5',
                         lint('forward-ref-a.md', 'forward-ref-b.md').stderr)

    def test_chunk_outside_a_fence(self):
        self.assertLintError(['chunk-in-list.md'], 'chunk-in-list.md:4',
                             ['must follow a ```cpp fence'])

    def test_code_wider_than_the_column(self):
        self.assertLintError(['long-line.md'], 'long-line.md:5', ['columns'])

    def test_chapter_names_the_build_can_order(self):
        result = run(['python3', os.path.join(TOOLS, 'noweb', 'lint.py'), '--book',
                      'tests/tools/lint/good.md'])
        self.assertEqual(result.returncode, 1)
        self.assertIn('tests/tools/lint/good.md:0: a chapter file is named NN-slug.md',
                      result.stderr)

    def test_missing_chapter_file(self):
        self.assertLintError(['no-such-chapter.md'], 'no-such-chapter.md:0',
                             ['cannot read chapter'])


class ChunksTest(unittest.TestCase):
    """tools/noweb/chunks.py, the one reading of the chunk grammar: what it
    hands the weave's Lua filters is what it read, byte for byte."""

    def test_the_weave_loads_the_chunks_as_read(self):
        tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, tmp)
        chapter = os.path.join(tmp, '01-quotes.md')
        code = 'auto s = "a\\"b\\\\"; // \u00e9 \x01 (a @<< 2) >> 1'
        with open(chapter, 'w', encoding='utf-8') as f:
            f.write('# Q\n\n```cpp\n<<lrt/q.h>>=\n%s\n    <<Part>>\n@ %%def s\n```\n\n'
                    '```cpp\n<<Part>>=\nint part;\n<<Unclosed>>=\n' % code)
        result = run(['python3', os.path.join(TOOLS, 'noweb', 'chunks.py'), '--lua',
                      chapter])
        self.assertEqual(result.returncode, 0, result.stderr)
        table = os.path.join(tmp, 'chunks.lua')
        with open(table, 'w', encoding='utf-8') as f:
            f.write(result.stdout)
        # texlua (Lua 5.3, as in pandoc) loads the table as the weave does.
        reader = os.path.join(tmp, 'show.lua')
        with open(reader, 'w') as f:
            f.write('for _, c in ipairs(dofile(arg[1]).chunks) do io.write(c.name, "|", '
                    'c.line, "|", c.ended_by, "|", table.concat(c.lines, "/"), "|", '
                    'table.concat(c.defs, ","), "|", #c.uses, "\\n") end\n')
        shown = run(['texlua', reader, table])
        self.assertEqual(shown.returncode, 0, shown.stderr)
        self.assertEqual(shown.stdout.split('\n'), [
            'lrt/q.h|4|@|%s/    <<Part>>|s|1' % code,
            'Part|11|definition|int part;||0',
            'Unclosed|13|eof|||0', ''])


class TangleTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, self.tmp)

    def tangle(self, *args):
        return run(['python3', os.path.join(TOOLS, 'noweb', 'tangle.py')] + list(args))

    def test_compiler_errors_point_into_the_chapter(self):
        chapter = os.path.join(self.tmp, '02-example.md')
        with open(chapter, 'w') as f:
            f.write('# Example\n\n```cpp\n<<lrt/example.cpp>>=\nint f() {\n'
                    '    <<Return something undeclared>>\n}\n@\n```\n\nText.\n\n'
                    '```cpp\n<<Return something undeclared>>=\nreturn undeclared;\n'
                    '@\n```\n')
        out = os.path.join(self.tmp, 'src')
        result = self.tangle('--line-directives', '--out', out, chapter)
        self.assertEqual(result.returncode, 0, result.stderr)
        compiled = run(['g++', '-std=c++17', '-c', os.path.join(out, 'lrt/example.cpp'),
                        '-o', os.path.join(self.tmp, 'example.o')])
        self.assertNotEqual(compiled.returncode, 0)
        self.assertIn(chapter + ':15:', compiled.stderr)
        self.assertIn('undeclared', compiled.stderr)

    def test_readable_tangle_names_fragments_and_removes_stale_files(self):
        out = os.path.join(self.tmp, 'tangled')
        os.makedirs(os.path.join(out, 'lrt'))
        stale = os.path.join(out, 'lrt', 'stale.h')
        open(stale, 'w').close()
        good = os.path.join(LINT_CASES, 'good.md')
        result = self.tangle('--out', out, good)
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(os.path.join(out, 'lrt', 'good.h')) as f:
            text = f.read()
        self.assertIn('// Compute the shifted value\n', text)
        self.assertIn('return (a << 2) >> 1;', text)
        self.assertNotIn('#line', text)
        self.assertFalse(os.path.exists(stale))
        self.assertEqual(os.stat(os.path.join(out, 'lrt', 'good.h')).st_mode & 0o777,
                         0o644)

    def test_fragment_is_named_once_per_expansion(self):
        # A fragment defined in three pieces and used once is named once, at
        # its first piece; one used in two places is named at each.
        chapter = os.path.join(self.tmp, '02-pieces.md')

        def chunk(name, *code):
            return '```cpp\n<<%s>>=\n%s\n@\n```\n\nText.\n\n' % (name, '\n'.join(code))
        with open(chapter, 'w') as f:
            f.write('# Pieces\n\n' +
                    chunk('lrt/pieces.h', '<<Constants>>', 'int f() {',
                          '    <<Return one>>', '}', 'int g() {',
                          '    <<Return one>>', '}') +
                    chunk('Constants', 'const int a = 1;') +
                    chunk('Return one', 'return 1;') +
                    chunk('Constants', 'const int b = 2;') +
                    chunk('Constants', 'const int c = 3;'))
        out = os.path.join(self.tmp, 'tangled')
        result = self.tangle('--out', out, chapter)
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(os.path.join(out, 'lrt', 'pieces.h')) as f:
            text = f.read()
        self.assertEqual(text.count('// Constants'), 1, text)
        self.assertIn('// Constants\nconst int a = 1;\nconst int b = 2;\n'
                      'const int c = 3;\n', text)
        self.assertEqual(text.count('    // Return one\n    return 1;\n'), 2, text)

        # The compiler's tangle has no comments, and a #line directive before
        # every piece, each pointing at that piece's own line.
        lines = os.path.join(self.tmp, 'lines')
        result = self.tangle('--line-directives', '--out', lines, chapter)
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(os.path.join(lines, 'lrt', 'pieces.h')) as f:
            text = f.read()
        self.assertNotIn('// ', text)
        with open(chapter) as f:
            source = f.read().split('\n')
        for code in ('const int a = 1;', 'const int b = 2;', 'const int c = 3;'):
            line = source.index(code) + 1
            self.assertIn('#line %d "%s"\n%s\n' % (line, chapter, code), text)

    def test_unchanged_files_keep_their_time(self):
        # make rebuilds what a tangle touched: a file whose text is the same
        # must not be written again, one whose text changed must be.
        chapter = os.path.join(self.tmp, '02-two.md')
        text = ('# Two\n\n```cpp\n<<lrt/a.h>>=\nint a();\n@\n```\n\nText.\n\n'
                '```cpp\n<<lrt/b.h>>=\nint b();\n@\n```\n')
        with open(chapter, 'w') as f:
            f.write(text)
        out = os.path.join(self.tmp, 'src')
        self.assertEqual(self.tangle('--out', out, chapter).returncode, 0)
        a, b = os.path.join(out, 'lrt', 'a.h'), os.path.join(out, 'lrt', 'b.h')
        for path in (a, b):
            os.utime(path, (1000000000, 1000000000))
        with open(chapter, 'w') as f:
            f.write(text.replace('int b();', 'long b();'))
        result = self.tangle('--out', out, chapter)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(os.stat(a).st_mtime, 1000000000)
        self.assertNotEqual(os.stat(b).st_mtime, 1000000000)
        with open(b) as f:
            self.assertIn('long b();', f.read())

    def test_undefined_fragment_fails_the_tangle(self):
        result = self.tangle('--out', os.path.join(self.tmp, 'out'),
                             os.path.join(LINT_CASES, 'undefined-use.md'))
        self.assertNotEqual(result.returncode, 0)
        self.assertIn('Body of f', result.stderr)


class IncrementalBuildTest(unittest.TestCase):
    """tools/make/asof.mk on a one-chapter book in a scratch checkout, with a
    compiler cache of its own: an edited header is recompiled, never taken
    from the cache, and a precompiled header that does not fit fails the
    build instead of being quietly ignored. Light flags (no -g, no -O2) keep
    the compiles short; the rules are those of the real build."""

    CHAPTER = ('# Value\n\n```cpp\n<<lrt/value.h>>=\n#pragma once\n'
               'inline int Value() { return %d; }\n@\n```\n')
    TEST = ('#include "lrt/value.h"\n#include <gtest/gtest.h>\n'
            'TEST(Value, IsOne) { EXPECT_EQ(Value(), 1); }\n')

    @classmethod
    def setUpClass(cls):
        # One cache for both tests: the second finds the first's entries.
        cls.ccache = tempfile.mkdtemp()

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.ccache)

    def setUp(self):
        self.tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, self.tmp)
        self.checkout = os.path.join(self.tmp, 'checkout')
        os.makedirs(os.path.join(self.checkout, 'chapters'))
        os.makedirs(os.path.join(self.checkout, 'tests', 'ch02'))
        os.symlink(TOOLS, os.path.join(self.checkout, 'tools'))
        with open(os.path.join(self.checkout, 'tests', 'ch02', 'test_value.cpp'), 'w') as f:
            f.write(self.TEST)
        # Run from make test, the environment holds the outer make's flags
        # (-s, its variables) and its exported variables: none may reach this
        # build.
        self.env = {k: v for k, v in os.environ.items() if k not in (
            'MAKEFLAGS', 'MFLAGS', 'MAKELEVEL', 'CHAPTERS', 'BUILD', 'FLOAT', 'SANITIZE')}
        self.env['CCACHE_DIR'] = self.ccache

    def asof_make(self, cxxflags, *args):
        """Runs tools/make/asof.mk as of the one chapter, in the checkout, printing
        its commands in full (V=1), which the tests read."""
        return subprocess.run(['make', '--no-print-directory', '-f', 'tools/make/asof.mk', 'ASOF=02',
                               'V=1',
                               'CHAPTERS=chapters/02-value.md', 'BUILD=build',
                               'CXXFLAGS=' + cxxflags] + list(args),
                              cwd=self.checkout, env=self.env, capture_output=True, text=True)

    def build_and_run(self, value):
        with open(os.path.join(self.checkout, 'chapters', '02-value.md'), 'w') as f:
            f.write(self.CHAPTER % value)
        for goal in ('tangle', 'tests'):
            result = self.asof_make('-std=c++17 -Wall -Werror', goal)
            if result.returncode != 0:
                return result
        self.assertIn('-include pch/test_pch.h', result.stdout)
        return subprocess.run([os.path.join(self.checkout, 'build/float/asof/02/tests/ch02')],
                              capture_output=True, text=True)

    def test_edited_header_is_compiled_again(self):
        for value, passes in ((1, True), (2, False), (1, True), (2, False)):
            result = self.build_and_run(value)
            self.assertEqual(result.returncode == 0, passes,
                             'Value() = %d:\n%s%s' % (value, result.stdout, result.stderr))

    def test_tests_get_line_tables_unless_told_full_debugging(self):
        # The flags of the test's compile (make -n: nothing is compiled),
        # from the real build's -g -O2.
        def test_compile(*extra):
            result = self.asof_make('-std=c++17 -g -O2 -Wall', '-n', *extra, 'tests')
            lines = [line for line in result.stdout.splitlines()
                     if '-c tests/ch02/test_value.cpp' in line]
            self.assertEqual(len(lines), 1, result.stdout + result.stderr)
            return lines[0].split()
        default, full = test_compile(), test_compile('TEST_DEBUG=-g')
        self.assertIn('-g1', default)
        self.assertNotIn('-g', default)
        self.assertIn('-g', full)
        self.assertNotIn('-g1', full)
        self.assertIn('-O1', full)

    def test_unfit_precompiled_header_fails_the_build(self):
        self.assertEqual(self.build_and_run(1).returncode, 0)
        pch = os.path.join(self.checkout, 'build/float/pch/test_pch.h.gch')
        with open(pch, 'wb') as f:
            f.write(b'not a precompiled header')
        os.remove(os.path.join(self.checkout, 'build/float/asof/02/obj/tests/ch02/test_value.o'))
        result = self.build_and_run(1)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn('test_pch.h.gch', result.stderr)


class RunTestsTest(unittest.TestCase):
    """tools/testing/runtests.py runs a test binary whose bytes equal an earlier
    one's only once (the code as of a later chapter often links exactly the
    same program), and reports its results under both labels."""

    # A stand-in for a GoogleTest binary: it notes each run in $RUNS_LOG and
    # writes the JSON report GoogleTest would, one test passing and, if FAILS
    # is set in its text, one failing.
    PROGRAM = """#!/usr/bin/env python3
import json, os, sys
FAILS = %s
with open(os.environ['RUNS_LOG'], 'a') as f:
    f.write(sys.argv[0] + '\\n')
tests = [{'name': 'Passes', 'status': 'RUN', 'result': 'COMPLETED'}]
if FAILS:
    tests.append({'name': 'Fails', 'status': 'RUN', 'result': 'COMPLETED',
                  'failures': [{'failure': 'expected 1'}]})
report = [a for a in sys.argv if a.startswith('--gtest_output=json:')][0]
with open(report[len('--gtest_output=json:'):], 'w') as f:
    json.dump({'testsuites': [{'name': 'Fake', 'testsuite': tests}]}, f)
sys.exit(1 if FAILS else 0)
"""

    def program(self, directory, fails):
        path = os.path.join(self.tmp, directory, 'ch03')
        os.makedirs(os.path.dirname(path))
        with open(path, 'w') as f:
            f.write(self.PROGRAM % fails)
        os.chmod(path, 0o755)
        return path

    def setUp(self):
        self.tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, self.tmp)

    def test_identical_binary_runs_once_and_reports_under_both_labels(self):
        same1, same2 = self.program('05', True), self.program('06', True)
        other = self.program('07', False)
        log = os.path.join(self.tmp, 'runs.log')
        result = subprocess.run(
            ['python3', os.path.join(TOOLS, 'testing', 'runtests.py'), '--jobs', '1',
             'asof05/ch03=' + same1, 'asof06/ch03=' + same2, 'asof07/ch03=' + other],
            capture_output=True, text=True, env=dict(os.environ, RUNS_LOG=log))
        with open(log) as f:
            self.assertEqual(sorted(f.read().split()), [same1, other])
        self.assertIn('FAILED: asof05/ch03 Fake.Fails', result.stdout)
        self.assertIn('FAILED: asof06/ch03 Fake.Fails', result.stdout)
        self.assertRegex(result.stdout, r'asof06/ch03 +1 passed, 1 failed '
                                        r'\(the program of asof05/ch03\)')
        self.assertEqual(result.stdout.strip().splitlines()[-1], 'tests: 3 passed, 2 failed')
        self.assertNotEqual(result.returncode, 0)

    # Two files of Python tests that can pass only side by side: each marks
    # that it started, then waits up to a minute for the other's mark.
    MEETS = """import os, time, unittest
class Meet(unittest.TestCase):
    def test_meets_the_other_file(self):
        here = os.path.dirname(os.path.abspath(__file__))
        open(os.path.join(here, '%s.started'), 'w').close()
        other = os.path.join(here, '%s.started')
        deadline = time.time() + 60
        while not os.path.exists(other) and time.time() < deadline:
            time.sleep(0.05)
        self.assertTrue(os.path.exists(other), 'the other file did not run alongside')
"""

    def python_tests(self, files):
        directory = os.path.join(self.tmp, 'pytests')
        os.makedirs(directory)
        for name, text in files.items():
            with open(os.path.join(directory, name), 'w') as f:
                f.write(text)
        return directory

    def run_python_tests(self, directory, jobs):
        return subprocess.run(['python3', os.path.join(TOOLS, 'testing', 'runtests.py'), '--jobs',
                               str(jobs), '--python-tests', directory],
                              capture_output=True, text=True, timeout=300)

    def test_python_test_files_run_side_by_side(self):
        directory = self.python_tests({'test_a.py': self.MEETS % ('a', 'b'),
                                       'test_b.py': self.MEETS % ('b', 'a')})
        result = self.run_python_tests(directory, 2)
        self.assertEqual(result.stdout.strip().splitlines()[-1], 'tests: 2 passed, 0 failed',
                         result.stdout)
        self.assertRegex(result.stdout, r'tools/test_a\.py +1 passed, 0 failed')

    def test_every_python_tests_option_runs(self):
        # make test CH=09 names two files; only the last one ran.
        directory = self.python_tests({
            'test_one.py': 'import unittest\n'
                           'class One(unittest.TestCase):\n'
                           '    def test_one(self):\n'
                           '        pass\n',
            'test_two.py': 'import unittest\n'
                           'class Two(unittest.TestCase):\n'
                           '    def test_two(self):\n'
                           '        self.fail("expected")\n'})
        result = subprocess.run(
            ['python3', os.path.join(TOOLS, 'testing', 'runtests.py'), '--jobs', '1',
             '--python-tests', os.path.join(directory, 'test_two.py'),
             '--python-tests', os.path.join(directory, 'test_one.py')],
            capture_output=True, text=True, timeout=300)
        self.assertIn('FAILED: tools test_two.Two.test_two', result.stdout)
        self.assertEqual(result.stdout.strip().splitlines()[-1], 'tests: 1 passed, 1 failed',
                         result.stdout)

    def test_python_file_that_exits_midway_is_a_failure(self):
        directory = self.python_tests({
            'test_exits.py': 'import os, unittest\n'
                             'class Exits(unittest.TestCase):\n'
                             '    def test_exits(self):\n'
                             '        os._exit(0)\n',
            'test_fails.py': 'import unittest\n'
                             'class Fails(unittest.TestCase):\n'
                             '    def test_passes(self):\n'
                             '        pass\n'
                             '    def test_fails(self):\n'
                             '        self.fail("expected")\n'})
        result = self.run_python_tests(directory, 1)
        self.assertIn('FAILED: tools/test_exits.py (no report)', result.stdout)
        self.assertIn('FAILED: tools test_fails.Fails.test_fails', result.stdout)
        self.assertEqual(result.stdout.strip().splitlines()[-1], 'tests: 1 passed, 2 failed')
        self.assertNotEqual(result.returncode, 0)


class WeaveTest(unittest.TestCase):
    """The filter's own reading of the chunks must match noweb's; what it
    writes for footers, code, examples, captions and citations."""

    def weave(self, text, *options, files=None):
        tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, tmp)
        for name, content in (files or {}).items():
            with open(os.path.join(tmp, name), 'w') as f:
                f.write(content)
        chapter = os.path.join(tmp, '01-weave.md')
        with open(chapter, 'w') as f:
            f.write(text)
        return run(['pandoc', chapter, '--lua-filter', os.path.join(TOOLS, 'book', 'weave.lua')] +
                   list(options) + ['-t', 'latex'], cwd=tmp)

    def test_an_exercise_escapes_a_fragment_name_as_a_chunk_header_does(self):
        # tools/book/exercises.lua and weave.lua share tools/book/latex_text.lua:
        # a ^ in a name is the ASCII character in both, not an accent over nothing.
        tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, tmp)
        chapter = os.path.join(tmp, '01-exercise.md')
        with open(chapter, 'w') as f:
            f.write('# Ch\n\n::: {.exercise #ex-1.1 points=1 title="T" '
                    'fragments="Square of x^2"}\nDo it.\n:::\n')
        result = run(['pandoc', chapter, '--lua-filter',
                      os.path.join(TOOLS, 'book', 'exercises.lua'), '-t', 'latex'], cwd=tmp)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn('\\fragmentname{Square of x\\textasciicircum{}2}{}', result.stdout)

    def test_chunks_are_numbered_and_linked(self):
        with open(os.path.join(LINT_CASES, 'good.md')) as f:
            result = self.weave(f.read())
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn('\\fragheader{chunk:1.1}{1.1}', result.stdout)
        self.assertIn('\\fragheader{chunk:1.2}{1.2}', result.stdout)
        self.assertIn('\\fraguse{', result.stdout)
        self.assertIn('\\fragnote{Used in}{\\chunkref{chunk:1.1}{1.1}}', result.stdout)
        self.assertIn('\\identindexentry{Shifted}', result.stdout)
        self.assertNotIn('@<<', result.stdout)

    def test_appendix_is_lettered(self):
        result = self.weave('# Ch\n\n```cpp\n<<lrt/x.h>>=\nint x;\n@\n```\n\n'
                            '# App {#sec:app .appendix}\n\nSee @sec:app.\n\n'
                            '```cpp\n<<lrt/y.h>>=\nint y;\n@\n```\n')
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn('\\fragheader{chunk:1.1}{1.1}', result.stdout)
        self.assertIn('\\fragheader{chunk:A.1}{A.1}', result.stdout)
        self.assertIn('Appendix~\\ref*{sec:app}', result.stdout)
        self.assertLess(result.stdout.index('\\appendix'), result.stdout.index('{App}'))

    def test_chapter_after_an_appendix_fails(self):
        result = self.weave('# App {.appendix}\n\nText.\n\n# Ch\n\nText.\n')
        self.assertNotEqual(result.returncode, 0)
        self.assertIn('stands after an appendix', result.stderr)

    def test_disagreement_with_noweb_fails(self):
        # Inside an HTML comment pandoc sees no code while noweb still tangles
        # the chunk: the book would not show code that is compiled.
        result = self.weave('# Ch\n\n```cpp\n<<lrt/x.h>>=\nint x;\n@\n```\n\n'
                            '<!--\n```cpp\n<<lrt/y.h>>=\nint y;\n@\n```\n-->\n')
        self.assertNotEqual(result.returncode, 0)
        self.assertIn('noweb reads', result.stderr)

    def test_reference_to_a_missing_label_fails(self):
        result = self.weave('# Ch {#sec:ch}\n\nSee @sec:nowhere and @sec:ch.\n')
        self.assertNotEqual(result.returncode, 0)
        self.assertIn('sec:nowhere', result.stderr)
        self.assertNotIn('sec:ch,', result.stderr)

    def test_numbered_equation(self):
        result = self.weave('# Ch\n\n$$ a = b $$ {#eq:ab}\n\nBy @eq:ab.\n')
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn('\\begin{equation} a = b \\label{eq:ab}\\end{equation}',
                      result.stdout)
        self.assertIn('Equation~(\\ref*{eq:ab})', result.stdout)


    def test_footer_names_the_neighbouring_pieces(self):
        # Four pieces of one fragment: each footer names the piece before and
        # the piece after it, not the whole chain.
        pieces = ''.join('```cpp\n<<Body>>=\nint x%d;\n@\n```\n\n' % i for i in range(4))
        result = self.weave('# Ch\n\n```cpp\n<<lrt/x.h>>=\n<<Body>>\n@\n```\n\n' + pieces)
        self.assertEqual(result.returncode, 0, result.stderr)
        footers = re.findall(r'\\fragfooter\{(.*)\}\\end\{fragment\}', result.stdout)
        self.assertEqual(len(footers), 5)
        first, second, third, last = footers[1:]
        self.assertIn('\\fragnote{Continued in}{\\chunkref{chunk:1.3}{1.3}}', first)
        self.assertNotIn('Continues', first)
        self.assertIn('\\fragnote{Continues}{\\chunkref{chunk:1.2}{1.2}}', second)
        self.assertIn('\\fragnote{Continued in}{\\chunkref{chunk:1.4}{1.4}}', second)
        self.assertNotIn('chunk:1.5', second)
        self.assertIn('\\fragnote{Continues}{\\chunkref{chunk:1.3}{1.3}}', third)
        self.assertIn('\\fragnote{Continues}{\\chunkref{chunk:1.4}{1.4}}', last)
        self.assertNotIn('Continued in', last)

    def test_fragment_records_its_lines_of_code(self):
        # The page layout keeps lines with the header and footer by number.
        result = self.weave('# Ch\n\n```cpp\n<<lrt/x.h>>=\nint a;\n\nint b;\n@\n```\n')
        self.assertEqual(result.returncode, 0, result.stderr)
        # Line 2 is blank, and blank lines do not count among those kept.
        self.assertIn('\\begin{fragment}{chunk:1.1}{3}{2}\\fragheader{chunk:1.1}', result.stdout)

    def test_caret_in_code_is_the_ascii_character(self):
        # \\^{} is a circumflex accent over nothing, a raised hat; \\lrtcaret{}
        # is the character as code fonts draw it.
        result = self.weave('# Ch\n\nSo `a ^ b` flips.\n\n```cpp\n<<lrt/x.h>>=\n'
                            'int f(int a, int b) { return a ^ b; }\n@\n```\n\n'
                            '```c++\nx ^= 1;\n```\n')
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertNotIn('\\^{}', result.stdout)
        self.assertEqual(result.stdout.count('\\lrtcaret{}'), 3)

    def test_fragment_examples_come_from_the_chunks(self):
        text = ('# Ch\n\n`Body`{.fragment-header}\n\nThe number `Body`{.fragment-number} '
                'and a use, `Body`{.fragment-use}.\n\n```cpp\n<<lrt/x.h>>=\nint a;\n'
                '<<Body>>\n@\n```\n\n```cpp\n<<Body>>=\nint b;\n@\n```\n')
        result = self.weave(text)
        self.assertEqual(result.returncode, 0, result.stderr)
        body_id = re.search(r'\\fragname\{(f\d+)\}\{Body\}', result.stdout).group(1)
        self.assertIn('\\fragheadersample{\\fragheaderline{%s}{chunk:1.2}{1.2}{def}}' % body_id,
                      result.stdout)
        self.assertIn('The number \\hyperref[chunk:1.2]{1.2}', result.stdout)
        self.assertIn('a use, \\fraguse{%s}.' % body_id, result.stdout)
        stale = self.weave(text.replace('`Body`{.fragment-use}', '`Bodies`{.fragment-use}'))
        self.assertNotEqual(stale.returncode, 0)
        self.assertIn('<<Bodies>>, which no chunk defines', stale.stderr)

    def test_figure_has_a_short_caption_for_the_list_of_figures(self):
        result = self.weave('# Ch\n\nSee @fig:a.\n\n![A box in the plane $x = 1.5$. Its '
                            'corners are marked, e.g. the lowest.](a.png){#fig:a}\n\n'
                            '```{=latex}\n\\begin{figure}\\caption{One sentence only.}'
                            '\\label{fig:b}\\end{figure}\n```\n')
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn('\\caption[{A box in the plane \\(x = 1.5\\).}]{A box in the plane',
                      result.stdout)
        self.assertIn('\\caption{One sentence only.}', result.stdout)
        # The first citation of a float is recorded for the layout check.
        self.assertIn('\\floatcite{fig:a}\\hyperref[fig:a]{Figure~\\ref*{fig:a}}',
                      result.stdout)

    def test_citations_and_references(self):
        bib = ('@article{Kay1986Ray, author = {Timothy L. Kay and James T. Kajiya},\n'
               'title = {Ray Tracing Complex Scenes}, journal = {Computer Graphics},\n'
               'year = {1986}}\n')
        result = self.weave('---\nbibliography: refs.bib\n---\n\n# Ch {#sec:ch}\n\n'
                            '@Kay1986Ray introduced slabs (@sec:ch).\n', '--citeproc',
                            files={'refs.bib': bib})
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn('Kay and Kajiya', result.stdout)
        self.assertIn('Chapter~\\ref*{sec:ch}', result.stdout)   # left to weave.lua
        refs = result.stdout.index('*{References}')
        self.assertLess(refs, result.stdout.index('Ray Tracing Complex'))
        self.assertLess(result.stdout.index('\\backmatter'), refs)
        self.assertLess(refs, result.stdout.index('\\begin{fragmentindex}'))


class LayoutCheckTest(unittest.TestCase):
    """tools/book/layout_check.py on layout records written by hand."""

    @staticmethod
    def fragment(label, pages, footer=None, blank=()):
        """The records of a fragment whose line i is on page pages[i - 1]
        (the header on the first line's page, the footer on the last's unless
        given) and blank where i is in blank, as tools/book/preamble.tex
        writes them: only the lines up to the third that is not blank, and
        from the third from the end, have records."""
        n = len(pages)
        code = [i for i in range(1, n + 1) if i not in blank]
        first, last = code[min(2, len(code) - 1)], code[max(-3, -len(code))]
        events = [('header', (label, n), pages[0])]
        events += [('blank' if i in blank else 'line', (label, i), pages[i - 1])
                   for i in range(1, n + 1) if i <= first or i >= last]
        return events + [('footer', label, footer or pages[-1])]

    WHOLE = [('header', ('chunk:2.1', 7), '10')] + \
        [('line', ('chunk:2.1', i), '10') for i in (1, 2, 3)] + \
        [('line', ('chunk:2.1', i), '11') for i in (5, 6, 7)] + \
        [('footer', 'chunk:2.1', '11')]

    def problems(self, events, labels=None):
        return layout_check.check(events, labels or {})

    def test_a_fragment_across_pages_is_fine(self):
        self.assertEqual(self.problems(self.WHOLE), [])
        self.assertEqual(self.problems(self.fragment('chunk:2.2', ['10'] * 3 + ['11'] * 3)),
                         [])
        # Short fragments kept on one page have fewer records, all checked.
        self.assertEqual(self.problems(self.fragment('chunk:2.3', ['12'] * 2)), [])

    def test_stranded_header(self):
        events = self.fragment('chunk:2.1', ['11'] * 4)
        events[0] = ('header', ('chunk:2.1', 4), '10')
        self.assertEqual(self.problems(events), [
            'page 10 ends with the header of fragment 2.1, whose first lines of code '
            'are on page 11'])

    def test_stranded_footer(self):
        self.assertEqual(self.problems(self.fragment('chunk:2.1', ['11'] * 4, footer='12')), [
            'page 12 opens with the footer of fragment 2.1, cut from its last lines of '
            'code on page 11'])

    def test_header_with_fewer_than_three_lines_ends_a_page(self):
        self.assertEqual(self.problems(self.fragment('chunk:2.1', ['10'] * 2 + ['11'] * 6)), [
            'page 10 ends with the header of fragment 2.1 and only 2 lines of its code; '
            'line 3 is on page 11'])
        self.assertEqual(self.problems(self.fragment('chunk:2.1', ['10'] + ['11'] * 6)), [
            'page 10 ends with the header of fragment 2.1 and only 1 line of its code; '
            'line 2 is on page 11'])

    def test_page_opening_with_fewer_than_three_lines_and_a_footer(self):
        # As on pages 54, 62, 73, ... of the book before it kept three lines.
        self.assertEqual(self.problems(self.fragment('chunk:2.1', ['10'] * 6 + ['11'] * 2)), [
            'page 11 opens with only 2 lines of fragment 2.1 before its footer; '
            'line 6 is on page 10'])
        self.assertEqual(self.problems(self.fragment('chunk:3.4', ['20'] * 4 + ['21'])), [
            'page 21 opens with only 1 line of fragment 3.4 before its footer; '
            'line 4 is on page 20'])

    def test_blank_lines_do_not_count(self):
        # A blank line and two lines of code are two lines of code.
        self.assertEqual(self.problems(self.fragment('chunk:3.7', ['97'] * 10 + ['98'] * 3,
                                                     blank={11})), [
            'page 98 opens with only 2 lines of fragment 3.7 before its footer; '
            'line 10 is on page 97'])
        self.assertEqual(self.problems(self.fragment('chunk:3.7', ['97', '97', '98', '98'] +
                                                     ['98'] * 9, blank={2})), [
            'page 97 ends with the header of fragment 3.7 and only 1 line of its code; '
            'line 3 is on page 98'])
        # With a third line of code, or blank lines inside the ones kept, it is fine.
        self.assertEqual(self.problems(self.fragment('chunk:3.7', ['97'] * 9 + ['98'] * 4,
                                                     blank={11})), [])
        self.assertEqual(self.problems(self.fragment('chunk:3.7', ['97'] * 4 + ['98'] * 6,
                                                     blank={2, 5})), [])

    def test_short_fragment_cut_in_two(self):
        # Two lines cannot be cut without leaving fewer than three at an end.
        self.assertEqual(self.problems(self.fragment('chunk:2.1', ['10', '11'])), [
            'page 10 ends with the header of fragment 2.1 and only 1 line of its code; '
            'line 2 is on page 11',
            'page 11 opens with only 1 line of fragment 2.1 before its footer; '
            'line 1 is on page 10'])

    def test_a_long_fragment_may_run_over_several_pages(self):
        self.assertEqual(self.problems(self.fragment('chunk:2.1', ['10'] * 3 + ['11'] * 50 +
                                                     ['12'] * 3)), [])

    def test_float_inside_a_fragment(self):
        events = self.WHOLE[:2] + [('float', 'figure 2.4', '11')] + self.WHOLE[2:] + \
                 [('float', 'figure 2.5', '11')]
        self.assertEqual(self.problems(events), [
            'page 11: figure 2.4 lands inside fragment 2.1 (pages 10-11)'])

    def test_float_far_from_its_first_citation(self):
        labels = {'figure 2.4': 'fig:far', 'figure 2.5': 'fig:near',
                  'figure 2.6': 'fig:early'}
        events = [('cite', 'fig:far', '10'), ('cite', 'fig:near', '10'),
                  ('cite', 'fig:far', '13'), ('float', 'figure 2.5', '13'),
                  ('float', 'figure 2.4', '14'), ('float', 'figure 2.6', '15'),
                  ('cite', 'fig:early', '17')] + \
                 [(k, w, p) for k, w, p in self.WHOLE]
        self.assertEqual(self.problems(events, labels), [
            'page 14: figure 2.4 (fig:far) is printed 4 pages after its first citation '
            'on page 10',
            'page 15: figure 2.6 (fig:early) is printed 2 pages before its first '
            'citation on page 17'])

    def test_float_never_cited(self):
        events = [('float', 'figure 3.3', '118'), ('float', 'figure 3.4', '119')]
        self.assertEqual(self.problems(events, {'figure 3.3': 'fig:disks'}), [
            'page 118: figure 3.3 (fig:disks) is never cited'])

    def test_missing_record_of_a_fragment(self):
        events = self.WHOLE[:2] + self.WHOLE[4:]
        problems = self.problems(events)
        self.assertEqual(len(problems), 1)
        self.assertIn('fragment 2.1: no record of its line 2 ', problems[0])
        problems = self.problems(self.WHOLE[:-1])
        self.assertEqual(len(problems), 1)
        self.assertIn('fragment 2.1: no record of its footer', problems[0])

    def test_reads_the_records_that_the_preamble_writes(self):
        tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, tmp)
        path = os.path.join(tmp, 'book.layout')
        with open(path, 'w') as f:
            f.write('header chunk:2.1 7 10\nline chunk:2.1 1 10\nfloat figure 2.1 11\n'
                    'footer chunk:2.1 11\ncite fig:x 9\n')
        self.assertEqual(layout_check.read_events(path), [
            ('header', ('chunk:2.1', 7), '10'), ('line', ('chunk:2.1', 1), '10'),
            ('float', 'figure 2.1', '11'), ('footer', 'chunk:2.1', '11'),
            ('cite', 'fig:x', '9')])
        with open(path, 'w') as f:
            f.write('header chunk:2.1 10\n')
        with self.assertRaises(SystemExit) as raised:
            layout_check.read_events(path)
        self.assertIn('book.layout:1: cannot read this layout line', str(raised.exception))


# How the fixture book sets its fragments: as the book does; without the keep
# rules (\\lrtkeepfalse), as the book was set before it kept fragments whole;
# and keeping two lines at either end where the rule is three (the book kept
# two with the footer before, and a page opened with two lines and a footer).
LAYOUT_SETTINGS = {'kept': '', 'loose': '\\lrtkeepfalse',
                   'two': '\\renewcommand{\\lrtkeepfirst}{2}\\renewcommand{\\lrtkeeplast}{2}'}


def layout_fixture(setting):
    """A chapter of 24 fragments of 2 to 9 lines between paragraphs of random
    length, one of 90 lines after a figure too tall for the rest of its page,
    a fourth-level heading that a reference cites, and then fragments of 12
    lines, the tenth blank, each on a new page below a space that leaves 4
    points less room than the one before, so that some page has to break
    each fragment at every line (or before it), set as LAYOUT_SETTINGS[setting]
    says."""
    rnd = random.Random(7)
    out = ['# Fixture {#sec:fixture}', '']
    if LAYOUT_SETTINGS[setting]:
        out += ['```{=latex}', LAYOUT_SETTINGS[setting], '```', '']
    out += ['## Section', '', '### Subsection', '', '#### Paragraph {#sec:paragraph}', '',
            'See @sec:paragraph.', '']
    words = 'the ray meets the box where its slabs overlap and the test says so'.split()
    uses = []
    for k in range(24):
        lines = rnd.randint(2, 9)
        out += [' '.join(rnd.choice(words) for _ in range(rnd.randint(20, 120))), '']
        if k == 12:
            out += ['```{=latex}', '\\begin{figure}\\centering'
                    '\\rule{2cm}{0.45\\textheight}\\caption{A tall figure.}\\end{figure}',
                    '```', '']
            lines = 90
        uses.append('Piece %d' % k)
        out += ['```cpp', '<<Piece %d>>=' % k]
        out += ['int v%d_%d = %d;' % (k, i, i) for i in range(lines)] + ['@', '```', '']
    for k, room in enumerate(range(200, 20, -4)):
        uses.append('Cut %d' % k)
        out += ['```{=latex}', '\\clearpage\\vspace*{\\dimexpr\\textheight-%dpt\\relax}' % room,
                '```', '', '```cpp', '<<Cut %d>>=' % k]
        out += ['int c%d_%d = %d;' % (k, i, i) if i != 9 else '' for i in range(12)]
        out += ['@', '```', '']
    out += ['```cpp', '<<lrt/fixture.h>>='] + ['<<%s>>' % u for u in uses] + ['@', '```', '']
    return '\n'.join(out)


class LayoutFixtureTest(unittest.TestCase):
    """The woven fixture book passes the layout check; the same book set
    without the keep rules, or keeping too few lines, fails it, naming pages
    and fragments."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp()
        cls.book = os.path.join(cls.tmp, 'book.md')
        with open(cls.book, 'w') as f:
            f.write('---\ntitle: "Layout fixture"\ndocumentclass: book\n'
                    'classoption: [11pt, openany]\n---\n')
        cls.results = {}
        for setting in LAYOUT_SETTINGS:
            chapter = os.path.join(cls.tmp, '01-fixture-%s.md' % setting)
            with open(chapter, 'w') as f:
                f.write(layout_fixture(setting))
            out = os.path.join(cls.tmp, 'out-%s' % setting)
            cls.results[setting] = (out, run([os.path.join(TOOLS, 'book', 'weave.sh'), out,
                                              cls.book, chapter]))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp)

    def messages(self, setting):
        _, result = self.results[setting]
        self.assertNotEqual(result.returncode, 0)
        return [l for l in result.stderr.splitlines() if l.startswith('layout: ')]

    def test_book_kept_whole_passes(self):
        out, result = self.results['kept']
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertNotIn('layout:', result.stderr)
        text = run(['pdftotext', os.path.join(out, 'book.pdf'), '-']).stdout
        # The fourth-level heading has no number; the reference names the
        # numbered section around it.
        self.assertIn('See Section 1.1.1.', text)
        self.assertNotIn('1.1.1.1', text)
        # The fragments below the spaces were cut, at three lines from either end.
        with open(os.path.join(out, 'book.layout')) as f:
            records = [line.split() for line in f]
        header_page = {r[1]: r[3] for r in records if r[0] == 'header'}
        cut = {r[1] for r in records if r[0] == 'line' and int(r[1].split('.')[1]) > 24
               and r[3] != header_page[r[1]]}
        self.assertGreater(len(cut), 10)

    def test_book_set_loose_fails_naming_page_and_fragment(self):
        messages = self.messages('loose')
        self.assertTrue(any(re.match(r'layout: page \d+ ends with the header of fragment '
                                     r'1\.\d+, whose first lines of code are on page \d+$',
                                     m) for m in messages), messages)
        self.assertTrue(any(re.match(r'layout: page \d+ opens with the footer of fragment '
                                     r'1\.\d+', m) for m in messages), messages)
        self.assertTrue(any(re.match(r'layout: page \d+: figure 1\.1 lands inside fragment '
                                     r'1\.13 ', m) for m in messages), messages)

    def test_book_keeping_two_lines_fails_naming_page_and_fragment(self):
        messages = self.messages('two')
        self.assertTrue(any(re.match(r'layout: page \d+ ends with the header of fragment '
                                     r'1\.\d+ and only 2 lines of its code; line 3 is on '
                                     r'page \d+$', m) for m in messages), messages)
        self.assertTrue(any(re.match(r'layout: page \d+ opens with only 2 lines of fragment '
                                     r'1\.\d+ before its footer; line 9 is on page \d+$', m)
                            for m in messages), messages)
        # Two lines are kept, never one.
        self.assertFalse([m for m in messages if 'only 1 line' in m], messages)

    def test_citation_of_a_missing_key_fails(self):
        chapter = os.path.join(self.tmp, '01-cite.md')
        with open(chapter, 'w') as f:
            f.write('# Ch\n\nAs @Nobody2000 said.\n\n```cpp\n<<lrt/x.h>>=\nint a;\n@\n```\n')
        result = run([os.path.join(TOOLS, 'book', 'weave.sh'), os.path.join(self.tmp, 'cite'),
                      self.book, chapter])
        self.assertNotEqual(result.returncode, 0)
        self.assertIn('Nobody2000', result.stderr)
        self.assertIn('bibliography does not have', result.stderr)


if __name__ == '__main__':
    unittest.main()
