"""Tests of the exercise machinery (docs/exercises.md): the markup's lint, the
student edition's stubs, the tangle filter, the exercise boxes of the weave,
the kits, the leak check and the validation.

They run on the fixture book in exercises/: two chapters, three exercises (one
with a generated stub, one with a stub block), public and hidden tests. Each
broken variant changes one thing in a copy of it, and its test asserts the
file:line the lint names.
"""
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tarfile
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
TOOLS = os.path.join(ROOT, 'tools')
FIXTURE = os.path.join(HERE, 'exercises')
CH1 = 'chapters/01-sums.md'
CH2 = 'chapters/02-means.md'
sys.path.insert(0, ROOT)
from tools.exercises import kit_common, leaks, markup  # noqa: E402


def run(cmd, cwd=ROOT):
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)


def read(path):
    with open(path, encoding='utf-8') as f:
        return f.read()


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'w', encoding='utf-8') as f:
        f.write(text)


def line_of(text, needle, occurrence=1):
    """1-based line number of the occurrence-th line containing needle."""
    found = [n for n, line in enumerate(text.split('\n'), 1) if needle in line]
    assert len(found) >= occurrence, 'no %r in fixture' % needle
    return found[occurrence - 1]


class Variant:
    """A copy of the fixture book in a temporary directory, edited."""

    def __init__(self, test):
        self.dir = tempfile.mkdtemp()
        test.addCleanup(shutil.rmtree, self.dir)
        shutil.copytree(FIXTURE, self.dir, dirs_exist_ok=True)

    def path(self, rel):
        return os.path.join(self.dir, rel)

    def text(self, rel):
        return read(self.path(rel))

    def replace(self, rel, old, new, count=1):
        text = self.text(rel)
        assert old in text, 'no %r in %s' % (old, rel)
        write(self.path(rel), text.replace(old, new, count))
        return self

    def lint(self):
        chapters = sorted(os.listdir(self.path('chapters')))
        return run(['python3', os.path.join(TOOLS, 'exercises', 'markup.py'), 'lint'] +
                   ['chapters/' + c for c in chapters], cwd=self.dir)


class LintTest(unittest.TestCase):
    def assertLintError(self, variant, where, words):
        result = variant.lint()
        self.assertEqual(result.returncode, 1, result.stderr)
        matching = [l for l in result.stderr.splitlines() if l.startswith(where + ': ')]
        self.assertTrue(matching, 'no error at %s in:\n%s' % (where, result.stderr))
        for word in words:
            self.assertIn(word, matching[0])

    def test_fixture_passes(self):
        result = Variant(self).lint()
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(result.stderr, '')

    def test_begin_without_end(self):
        v = Variant(self).replace(CH2, '// END SOLUTION\n', '')
        self.assertLintError(v, '%s:%d' % (CH2, line_of(v.text(CH2), 'BEGIN SOLUTION')),
                             ['never closed', 'END SOLUTION'])

    def test_end_without_begin(self):
        v = Variant(self).replace(CH2, '// BEGIN SOLUTION\n', '')
        self.assertLintError(v, '%s:%d' % (CH2, line_of(v.text(CH2), 'END SOLUTION')),
                             ['without a matching BEGIN'])

    def test_nested_markers(self):
        v = Variant(self).replace(CH2, 'double total = 0;\n',
                                  'double total = 0;\n// BEGIN SOLUTION\n')
        self.assertLintError(v, '%s:%d' % (CH2, line_of(v.text(CH2), 'BEGIN SOLUTION', 2)),
                             ['do not nest'])

    def test_marker_in_prose(self):
        v = Variant(self).replace(CH2, 'Compute the mean of the elements',
                                  '// END STUB\nCompute the mean of the elements')
        self.assertLintError(v, '%s:%d' % (CH2, line_of(v.text(CH2), 'END STUB')),
                             ['outside a code chunk'])

    def test_marker_in_a_code_block_that_is_not_a_chunk(self):
        v = Variant(self).replace(CH1, 'This chapter adds up numbers.\n',
                                  'This chapter adds up numbers.\n\n```c++\n'
                                  '// BEGIN SOLUTION\nint x;\n// END SOLUTION\n```\n')
        self.assertLintError(v, '%s:6' % CH1, ['outside a code chunk'])

    def test_malformed_marker(self):
        v = Variant(self).replace(CH2, '// END SOLUTION', '//END SOLUTION')
        self.assertLintError(v, '%s:%d' % (CH2, line_of(v.text(CH2), '//END SOLUTION')),
                             ['malformed exercise marker'])

    def test_stub_block_must_follow_the_solution(self):
        v = Variant(self).replace(CH1, '// END SOLUTION\n// BEGIN STUB',
                                  '// END SOLUTION\n\n// BEGIN STUB')
        self.assertLintError(v, '%s:%d' % (CH1, line_of(v.text(CH1), 'BEGIN STUB')),
                             ['must follow END SOLUTION'])

    def test_fragment_use_inside_a_solution(self):
        v = Variant(self).replace(CH2, 'double total = 0;\n',
                                  'double total = 0;\n<<lrt/means.h>>\n')
        self.assertLintError(v, '%s:%d' % (CH2, line_of(v.text(CH2), '<<lrt/means.h>>', 2)),
                             ['fragment use <<lrt/means.h>>', 'solution'])

    def test_exercise_without_id(self):
        v = Variant(self).replace(CH2, '#ex-2.1 ', '')
        self.assertLintError(v, '%s:%d' % (CH2, line_of(v.text(CH2), '.exercise')),
                             ['without an id'])

    def test_exercise_without_points(self):
        v = Variant(self).replace(CH2, 'points=4 ', '')
        self.assertLintError(v, '%s:%d' % (CH2, line_of(v.text(CH2), '.exercise')),
                             ['ex-2.1', 'no points='])

    def test_points_not_a_number(self):
        v = Variant(self).replace(CH2, 'points=4 ', 'points=four ')
        self.assertLintError(v, '%s:%d' % (CH2, line_of(v.text(CH2), '.exercise')),
                             ['points=four', 'positive integer'])

    def test_id_of_another_chapter(self):
        v = Variant(self).replace(CH2, '#ex-2.1 ', '#ex-3.1 ')
        self.assertLintError(v, '%s:%d' % (CH2, line_of(v.text(CH2), '.exercise')),
                             ['ex-3.1', "chapter's"])

    def test_id_that_is_not_the_exercise_s_number_in_its_chapter(self):
        # The weave numbers ungraded exercises and graded ones in one sequence
        # (tools/book/exercises.lua): one put before ex-2.1 makes it 2.2.
        v = Variant(self).replace(CH2, '::: {.exercise #ex-2.1',
                                  '[Before.]{.problem #ex:before} A question.\n\n'
                                  '::: {.exercise #ex-2.1')
        self.assertLintError(v, '%s:%d' % (CH2, line_of(v.text(CH2), '.exercise')),
                             ['ex-2.1 is exercise 2.2', 'must be ex-2.2'])

    def test_exercise_without_hint(self):
        v = Variant(self).replace(CH2, ' hint="Add in `double`."', '')
        self.assertLintError(v, '%s:%d' % (CH2, line_of(v.text(CH2), '.exercise')),
                             ['ex-2.1', 'no hint'])

    def test_unknown_section(self):
        v = Variant(self).replace(CH2, 'section=sec:arithmetic-mean', 'section=sec:nowhere')
        self.assertLintError(v, '%s:%d' % (CH2, line_of(v.text(CH2), '.exercise')),
                             ['sec:nowhere', 'not the id of a header'])

    def test_duplicate_ids(self):
        v = Variant(self).replace(CH1, '#ex-1.2 ', '#ex-1.1 ')
        text = v.text(CH1)
        self.assertLintError(v, '%s:%d' % (CH1, line_of(text, '#ex-1.1', 2)),
                             ['duplicate exercise id ex-1.1',
                              'first at %s:%d' % (CH1, line_of(text, '#ex-1.1'))])

    def test_unknown_fragment(self):
        v = Variant(self).replace(CH2, 'fragments="Compute the mean of v"',
                                  'fragments="Compute the mean of v; No such thing"')
        self.assertLintError(v, '%s:%d' % (CH2, line_of(v.text(CH2), '.exercise')),
                             ['<<No such thing>>', 'not defined in this chapter'])

    def test_solution_that_belongs_to_no_exercise(self):
        v = Variant(self).replace(CH1, 'inline int Twice(int v) { return 2 * v; }\n',
                                  'inline int Twice(int v) {\n    // BEGIN SOLUTION\n'
                                  '    return 2 * v;\n    // END SOLUTION\n}\n')
        text = v.text(CH1)
        self.assertLintError(v, '%s:%d' % (CH1, line_of(text, '// BEGIN SOLUTION', 2)),
                             ['<<Sum inline functions>>', 'belongs to no exercise'])

    def test_exercise_without_tests(self):
        v = Variant(self).replace('tests/ch02/test_means.cpp', 'TEST(Ex2_1_Mean,',
                                  'TEST(Mean,')
        self.assertLintError(v, '%s:%d' % (CH2, line_of(v.text(CH2), '.exercise')),
                             ['ex-2.1 has no tests', 'Ex2_1_', 'tests/ch02/'])

    def test_exercise_without_hidden_tests(self):
        v = Variant(self)
        os.remove(v.path('tests/hidden/ch02/test_means_hidden.cpp'))
        self.assertLintError(v, '%s:%d' % (CH2, line_of(v.text(CH2), '.exercise')),
                             ['ex-2.1 has no hidden tests', 'tests/hidden/ch02/'])

    def test_no_hidden_tests_needed_without_a_hidden_directory(self):
        v = Variant(self)
        shutil.rmtree(v.path('tests/hidden'))
        result = v.lint()
        self.assertEqual(result.returncode, 0, result.stderr)

    def test_suite_naming_an_unknown_exercise(self):
        v = Variant(self).replace('tests/ch02/test_means.cpp', 'TEST(Mean, EmptyVectorThrows)',
                                  'TEST(Ex2_9_Mean, EmptyVectorThrows)')
        path = 'tests/ch02/test_means.cpp'
        self.assertLintError(v, '%s:%d' % (path, line_of(v.text(path), 'Ex2_9_Mean')),
                             ['Ex2_9_Mean', 'ex-2.9', 'does not exist'])

    def test_hidden_suite_naming_an_unknown_exercise(self):
        path = 'tests/hidden/ch01/test_sums_hidden.cpp'
        v = Variant(self).replace(path, 'Ex1_2_ClampHidden', 'Ex1_7_ClampHidden')
        self.assertLintError(v, '%s:%d' % (path, line_of(v.text(path), 'Ex1_7_')),
                             ['ex-1.7', 'does not exist'])

    def test_hidden_suite_naming_no_exercise(self):
        path = 'tests/hidden/ch01/test_sums_hidden.cpp'
        v = Variant(self).replace(path, 'Ex1_2_ClampHidden', 'ClampHidden')
        self.assertLintError(v, '%s:%d' % (path, line_of(v.text(path), 'ClampHidden')),
                             ['names no exercise'])

    def test_suite_of_an_exercise_of_another_chapter(self):
        path = 'tests/ch02/test_means.cpp'
        v = Variant(self).replace(path, 'TEST(Mean, TwiceStillWorks)',
                                  'TEST(Ex1_2_Twice, StillWorks)')
        self.assertLintError(v, '%s:%d' % (path, line_of(v.text(path), 'Ex1_2_Twice')),
                             ['ex-1.2 of chapter 01', 'tests/ch01/'])

    def test_malformed_exercise_suite(self):
        path = 'tests/ch02/test_means.cpp'
        v = Variant(self).replace(path, 'TEST(Mean, TwiceStillWorks)',
                                  'TEST(Ex2Mean, TwiceStillWorks)')
        self.assertLintError(v, '%s:%d' % (path, line_of(v.text(path), 'Ex2Mean')),
                             ['looks like an exercise', 'ExN_K_Name'])

    def test_exercise_test_declared_with_TEST(self):
        # Grading could not run it in rounds, and nothing says it reaches the
        # exercise through its calls.
        v = Variant(self).replace('tests/ch01/test_sums.cpp',
                                  'EXERCISE_TEST(Ex1_2_Clamp, InsideAndOutside)',
                                  'TEST(Ex1_2_Clamp, InsideAndOutside)')
        self.assertLintError(v, 'tests/ch01/test_sums.cpp:%d' % line_of(
            v.text('tests/ch01/test_sums.cpp'), 'TEST(Ex1_2_Clamp, InsideAndOutside) {'),
            ['Ex1_2_Clamp.InsideAndOutside', 'declared with TEST', 'EXERCISE_TEST'])

    def test_hidden_test_with_a_public_name(self):
        v = Variant(self).replace('tests/hidden/ch01/test_sums_hidden.cpp',
                                  'EXERCISE_TEST(Ex1_2_ClampHidden, RangeOfOneValue)',
                                  'EXERCISE_TEST(Ex1_2_Clamp, InsideAndOutside)')
        self.assertLintError(v, 'tests/hidden/ch01/test_sums_hidden.cpp:%d' % line_of(
            v.text('tests/hidden/ch01/test_sums_hidden.cpp'),
            'EXERCISE_TEST(Ex1_2_Clamp, InsideAndOutside) { EXPECT_EQ(ex::Clamp(7, 3, 3), 3); }'),
            ['hidden test Ex1_2_Clamp.InsideAndOutside has the name of a public test '
             '(tests/ch01/test_sums.cpp:'])

    def test_make_lint_runs_the_exercise_lint(self):
        result = run(['make', '-n', 'lint'])
        self.assertIn('tools/exercises/markup.py lint', result.stdout)


class StudentEditionTest(unittest.TestCase):
    def student(self, chapter):
        result = run(['python3', os.path.join(TOOLS, 'exercises', 'markup.py'), 'student', chapter],
                     cwd=FIXTURE)
        self.assertEqual(result.returncode, 0, result.stderr)
        return result.stdout

    def test_generated_stub_names_exercise_fragment_and_section(self):
        text = self.student(CH1)
        self.assertNotIn('sumOfSquares', text)
        self.assertIn('// BEGIN SOLUTION\nthrow std::logic_error(\n', text)
        message = ''.join(re.findall(r'"((?:[^"\\]|\\.)*)"',
                                     text.split('throw std::logic_error(')[1].split(');')[0]))
        self.assertEqual(message, 'Exercise ex-1.1 is not done yet: write <Add up the '
                         'squares of v> (Section 1.1, Sums of Squares)')

    def test_stub_block_replaces_the_solution(self):
        text = self.student(CH1)
        self.assertNotIn('return v < lo', text)
        self.assertNotIn('BEGIN STUB', text)
        self.assertNotIn('NOT IMPLEMENTED', text)
        self.assertIn('// BEGIN SOLUTION\n(void)v;\nthrow std::logic_error(\n'
                      '    "Exercise ex-1.2 is not done yet', text)
        # Everything outside the regions is unchanged.
        original = read(os.path.join(FIXTURE, CH1))
        self.assertEqual(text.split('<<Add up the squares of v>>=')[0],
                         original.split('<<Add up the squares of v>>=')[0])

    def test_later_stub_message_is_the_one_make_test_skips_on(self):
        # tests/calls/rpc.h recognizes a later assignment's stub by its
        # words; the two must agree.
        book = markup.load([os.path.join(FIXTURE, CH1)], root=FIXTURE, tests=False)
        message = markup.stub_message(book.exercises[1], 'Clamp v to the range', True)
        self.assertEqual(message, 'Exercise ex-1.2 comes with a later assignment: leave '
                         '<Clamp v to the range> (Section 1.2, Clamping) as it is for now')
        rpc = read(os.path.join(ROOT, 'tests', 'calls', 'rpc.h'))
        self.assertIn('" %s: "' % markup.LATER_STUB, rpc)

    def test_stub_lines_fit_the_column(self):
        lines = markup.throw_lines(' ' * 12, 'Exercise ex-6.12 is not done yet: write <'
                                      + 'A very long fragment name ' * 5 + '"quoted" \\ '
                                      + 'x' * 100 + '>')
        self.assertTrue(all(len(l) <= 80 for l in lines), '\n'.join(lines))
        literal = ''.join(re.findall(r'"((?:[^"\\]|\\.)*)"', '\n'.join(lines[1:])))
        self.assertIn('\\"quoted\\" \\\\ ', literal)
        self.assertTrue(lines[-1].endswith('");'))

    def test_student_chapters_pass_both_lints(self):
        tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, tmp)
        shutil.copytree(os.path.join(FIXTURE, 'tests'), os.path.join(tmp, 'tests'))
        shutil.rmtree(os.path.join(tmp, 'tests', 'hidden'))
        for chapter in (CH1, CH2):
            write(os.path.join(tmp, chapter), self.student(chapter))
        for tool in (('noweb', 'lint.py'), ('exercises', 'markup.py')):
            cmd = ['python3', os.path.join(TOOLS, *tool)] + (['lint'] if tool[0] ==
                                                             'exercises' else [])
            result = run(cmd + [CH1, CH2], cwd=tmp)
            self.assertEqual(result.returncode, 0, tool[1] + ': ' + result.stderr)


class FilterTest(unittest.TestCase):
    """tools/noweb/tangle.py runs tools/noweb/markup_filter.py: no markers, no stubs."""

    def tangle(self, chapter_dir, *options):
        out = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, out)
        chapters = sorted('chapters/' + c for c in os.listdir(os.path.join(chapter_dir,
                                                                           'chapters')))
        result = run(['python3', os.path.join(TOOLS, 'noweb', 'tangle.py'), '--out', out] +
                     list(options) + chapters, cwd=chapter_dir)
        return result, out

    def test_tangle_has_solutions_and_no_markup(self):
        result, out = self.tangle(FIXTURE)
        self.assertEqual(result.returncode, 0, result.stderr)
        code = read(os.path.join(out, 'lrt', 'sums.h')) + read(os.path.join(out, 'lrt',
                                                                             'sums.cpp'))
        self.assertIn('    return v < lo ? lo : (v > hi ? hi : v);\n', code)
        self.assertIn('sumOfSquares += static_cast<long>(value) * value;', code)
        for text in ('BEGIN', 'END', 'STUB', '(void)v', 'NOT IMPLEMENTED'):
            self.assertNotIn(text, code)

    def test_line_directives_survive_dropped_lines(self):
        v = Variant(self).replace(CH1, '    <<Clamp v to the range>>\n}',
                                  '    <<Clamp v to the range>>\n    undeclared();\n}')
        v.replace(CH1, '// END STUB\n@', '// END STUB\nundeclaredToo();\n@')
        result, out = self.tangle(v.dir, '--line-directives')
        self.assertEqual(result.returncode, 0, result.stderr)
        compiled = run(['g++', '-std=c++17', '-fsyntax-only', '-I', out,
                        os.path.join(out, 'lrt', 'sums.cpp')], cwd=v.dir)
        text = v.text(CH1)
        self.assertIn('%s:%d:' % (CH1, line_of(text, 'undeclared();')), compiled.stderr)
        self.assertIn('%s:%d:' % (CH1, line_of(text, 'undeclaredToo();')), compiled.stderr)

    def test_broken_markup_stops_the_tangle(self):
        v = Variant(self).replace(CH2, '// END SOLUTION\n', '')
        result, _ = self.tangle(v.dir)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn('markup_filter: %s:' % CH2, result.stderr)
        self.assertIn('never closed', result.stderr)


class WeaveTest(unittest.TestCase):
    def test_exercise_box(self):
        result = run(['pandoc', CH1, '--lua-filter', os.path.join(TOOLS, 'book', 'exercises.lua'),
                      '--lua-filter', os.path.join(TOOLS, 'book', 'weave.lua'), '-t', 'latex'],
                     cwd=FIXTURE)
        self.assertEqual(result.returncode, 0, result.stderr)
        latex = result.stdout
        self.assertIn('\\label{ex-1.1}\\textbf{Exercise 1.1}', latex)
        self.assertIn('\\textsf{3 points}', latex)
        self.assertIn('\\emph{Hint:} Square in \\texttt{long}', latex)
        self.assertIn('\\emph{Hint:} Two comparisons suffice; see', latex)
        self.assertIn('\\hyperref[sec:clamping]', latex)
        self.assertIn('\\textsf{Tests:}~\\texttt{Ex1\\_2\\_*}', latex)
        self.assertIn('\\fragmentname{Clamp v to the range}{}', latex)
        for text in ('BEGIN SOLUTION', 'END SOLUTION', 'BEGIN STUB', 'NOT IMPLEMENTED',
                     '(void)v'):
            self.assertNotIn(text, latex)
        self.assertIn('\\NormalTok{ lo }\\OperatorTok{?}\\NormalTok{ lo }', latex)


def build_kits(test, src, out, chapters=(), book=False):
    result = run(['python3', os.path.join(TOOLS, 'exercises', 'kits.py'), 'build', '--src', src,
                  '--out', out] + ([] if book else ['--no-book']) + list(chapters))
    test.assertEqual(result.returncode, 0, result.stdout + result.stderr)
    return result


class KitTest(unittest.TestCase):
    """One pair of kits of the whole fixture book, with its PDFs."""

    @classmethod
    def setUpClass(cls):
        cls.out = tempfile.mkdtemp()
        cls.result = run(['python3', os.path.join(TOOLS, 'exercises', 'kits.py'), 'build',
                          '--src', FIXTURE, '--out', cls.out])
        cls.student = os.path.join(cls.out, 'student')
        cls.solution = os.path.join(cls.out, 'solution')

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.out)

    def setUp(self):
        self.assertEqual(self.result.returncode, 0, self.result.stdout + self.result.stderr)

    def test_student_kit(self):
        s = self.student
        for rel in ('Makefile', 'README.md', 'book.pdf', 'exercises.json', 'book.md',
                    CH1, CH2, 'tests/ch01/test_sums.cpp', 'tools/make/exercises.mk',
                    'tools/noweb/tangle.py', 'tests/tools/test_toolchain.py',
                    'tangled/lrt/sums.cpp'):
            self.assertTrue(os.path.isfile(os.path.join(s, rel)), rel)
        # The grader's tests grade the repository's solutions and could only
        # fail in a student kit; a student's make test must not run them.
        for rel in ('tests/hidden', 'build', 'tests/tools/exercises',
                    'tests/tools/test_exercises.py', 'tests/tools/test_grade.py'):
            self.assertFalse(os.path.exists(os.path.join(s, rel)), rel)
        tangled = read(os.path.join(s, 'tangled/lrt/sums.cpp'))
        self.assertIn('"Exercise ex-1.1 is not done yet: write <Add up the squares of v> "',
                      tangled)
        self.assertNotIn('BEGIN SOLUTION', tangled)
        readme = read(os.path.join(s, 'README.md'))
        self.assertIn("make test CH=01 GTEST_FILTER='Ex1_1_*'", readme)
        self.assertIn('| 1.2 | 2 | Clamping | `chapters/01-sums.md` | Section 1.2 | `Ex1_2_*` |',
                      readme)
        self.assertNotIn('{{', readme)
        manifest = json.loads(read(os.path.join(s, 'exercises.json')))
        self.assertEqual([e['id'] for e in manifest['exercises']], ['ex-1.1', 'ex-1.2',
                                                                    'ex-2.1'])
        self.assertEqual(manifest['points'], 9)
        self.assertNotIn('hidden_tests', manifest['exercises'][0])
        with open(os.path.join(s, 'book.pdf'), 'rb') as f:
            pdf = leaks.pdf_text(f.read())
        self.assertIn('Exercise 1.2', pdf)
        self.assertIn('Hint: Two comparisons suffice', pdf)
        self.assertIn('"Exercise ex-2.1 is not done yet', pdf)

    def test_solution_kit(self):
        s = self.solution
        self.assertTrue(os.path.isfile(os.path.join(s, 'tests/hidden/ch01/test_sums_hidden.cpp')))
        self.assertEqual(read(os.path.join(s, CH1)), read(os.path.join(FIXTURE, CH1)))
        tangled = read(os.path.join(s, 'tangled/lrt/sums.cpp'))
        self.assertIn('sumOfSquares += static_cast<long>(value) * value;', tangled)
        self.assertNotIn('BEGIN SOLUTION', tangled)
        manifest = json.loads(read(os.path.join(s, 'exercises.json')))
        self.assertEqual(manifest['exercises'][2]['hidden_tests'],
                         ['Ex2_1_MeanHiddenCases.MixedSignsCancel'])

    def test_tarballs(self):
        for edition in ('student', 'solution'):
            with tarfile.open(os.path.join(self.out, 'lrt-%s.tar.gz' % edition)) as tar:
                names = set(tar.getnames())
            self.assertIn('lrt-%s/%s' % (edition, CH1), names)
            self.assertIn('lrt-%s/book.pdf' % edition, names)
            self.assertEqual(any('/tests/hidden/' in n for n in names),
                             edition == 'solution')

    def test_web_pages(self):
        # Both kits have the book as web pages too; the leak check reads their
        # text, so the solution kit's pages, checked as a student kit's, leak.
        def text(edition):
            pages = sorted(glob.glob(os.path.join(self.out, edition, 'html', '*.html')))
            self.assertTrue(pages, edition)
            return '\n'.join(leaks.html_text(read(p)) for p in pages)
        student, solution = text('student'), text('solution')
        self.assertIn('Exercise 1.2', student)
        self.assertIn('"Exercise ex-2.1 is not done yet', student)
        line = 'sumOfSquares += static_cast<long>(value) * value;'
        self.assertNotIn(line, student)
        self.assertIn(line, solution)
        problems = '\n'.join(self.leaks(self.out, 'solution'))
        self.assertRegex(problems, r'solution/html/01-sums\.html:\d+: solution of ex-1\.1')
        self.assertRegex(problems, r'lrt-solution\.tar\.gz:lrt-solution/html/\S+\.html:\d+:')

    def copy_of_student_kit(self):
        out = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, out)
        shutil.copytree(self.student, os.path.join(out, 'student'))
        return out

    def leaks(self, out, edition='student'):
        return leaks.find(out, FIXTURE, edition)

    def test_no_leaks(self):
        self.assertEqual(self.leaks(self.out), [])

    def test_planted_solution_line_is_found(self):
        out = self.copy_of_student_kit()
        path = os.path.join(out, 'student', 'tests', 'ch01', 'test_sums.cpp')
        write(path, read(path) + '// return total / static_cast<double>( v.size() );\n')
        problems = self.leaks(out)
        self.assertEqual(len(problems), 1, problems)
        self.assertIn('student/tests/ch01/test_sums.cpp:%d: solution of ex-2.1 (%s:%d)'
                      % (line_of(read(path), 'total /'), CH2,
                         line_of(read(os.path.join(FIXTURE, CH2)), 'total /')), problems[0])

    def test_planted_pair_of_solution_lines_is_found(self):
        # Two consecutive solution lines, each of which also stands elsewhere
        # in the source (so neither alone is a finding), found together.
        v = Variant(self)
        pair = ('sumOfSquares += static_cast<long>(value) * value;\n'
                'return sumOfSquares;\n')
        v.replace('tests/ch02/test_means.cpp', '#include <stdexcept>\n',
                  '#include <stdexcept>\n#if 0\n' + pair + '#endif\n')
        out = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, out)
        result = run(['python3', os.path.join(TOOLS, 'exercises', 'kits.py'), 'build', '--src',
                      v.dir, '--out', out, '--no-book'])
        self.assertNotEqual(result.returncode, 0)
        problems = [l for l in result.stderr.splitlines()
                    if l.startswith('leak: student/tests/ch02/test_means.cpp')]
        self.assertEqual(len(problems), 1, result.stderr)
        self.assertIn('solution of ex-1.1 (%s:%d): sumOfSquares += static_cast<long>(value) '
                      '* value; / return sumOfSquares;' % (
                          CH1, line_of(read(os.path.join(FIXTURE, CH1)), 'sumOfSquares +=')),
                      problems[0])

    def test_planted_hidden_test_name_is_found(self):
        out = self.copy_of_student_kit()
        path = os.path.join(out, 'student', 'README.md')
        write(path, read(path) + '\nGrading also runs MixedSignsCancel.\n')
        problems = self.leaks(out)
        self.assertEqual(len(problems), 1, problems)
        self.assertIn('student/README.md:', problems[0])
        self.assertIn('hidden test name MixedSignsCancel', problems[0])

    def test_leaks_in_the_pdf_and_tarball_are_found(self):
        # The solution kit, checked as if it were a student kit, leaks
        # everywhere: in its chapters, its tangle, its hidden tests, the text
        # of its PDF and its tarball.
        problems = '\n'.join(self.leaks(self.out, 'solution'))
        for where in ('solution/book.pdf:', 'solution/tangled/lrt/sums.cpp:',
                      'solution/chapters/02-means.md:', 'lrt-solution.tar.gz:lrt-solution/'
                      'book.pdf:', 'solution/tests/hidden/ch01/test_sums_hidden.cpp: a '
                      'hidden test file'):
            self.assertIn(where, problems)
        self.assertRegex(problems, r'solution/book.pdf:\d+: solution of ex-1.2 '
                         r'\(chapters/01-sums.md:\d+\): return v < lo')

    def test_chosen_chapters(self):
        out = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, out)
        build_kits(self, FIXTURE, out, ['2'])
        student = os.path.join(out, 'student')
        # Chapter 1 is not chosen: it stays as written, with its solutions.
        self.assertEqual(read(os.path.join(student, CH1)), read(os.path.join(FIXTURE, CH1)))
        self.assertIn('Exercise ex-2.1 is not done yet', read(os.path.join(student, CH2)))
        manifest = json.loads(read(os.path.join(student, 'exercises.json')))
        self.assertEqual([e['id'] for e in manifest['exercises']], ['ex-2.1'])
        self.assertEqual(leaks.find(out, FIXTURE), [])

    def test_unknown_chapter_is_an_error(self):
        result = run(['python3', os.path.join(TOOLS, 'exercises', 'kits.py'), 'build', '--src',
                      FIXTURE, '--out', os.path.join(self.out, 'x'), '--no-book', '07'])
        self.assertNotEqual(result.returncode, 0)
        self.assertIn('no chapter 07', result.stderr)


class PlanKitTest(unittest.TestCase):
    """The kits of one assignment of a course plan (docs/course.md), of the
    fixture book: ex-2.1 now, worth 10; ex-1.2 in the next assignment, so a
    stub in this kit although its chapter comes first; ex-1.1 in no
    assignment, so solved."""

    PLAN = ('title = "fixture course"\n\n'
            '[[assignment]]\nname = "first"\nexercises = ["ex-2.1"]\n'
            'points = { "ex-2.1" = 10 }\n\n'
            '[[assignment]]\nname = "second"\nexercises = ["ex-1.2"]\n')

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp()
        cls.plan = os.path.join(cls.tmp, 'course.toml')
        write(cls.plan, cls.PLAN)
        cls.out = os.path.join(cls.tmp, 'first')
        cls.result = run(['python3', os.path.join(TOOLS, 'exercises', 'kits.py'), 'build',
                          '--src', FIXTURE, '--out', cls.out, '--no-book',
                          '--plan', cls.plan, '--assignment', 'first'])

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp)

    def setUp(self):
        self.assertEqual(self.result.returncode, 0, self.result.stdout + self.result.stderr)

    def test_later_assignments_stay_stubs(self):
        student = os.path.join(self.out, 'student')
        ch1, ch2 = read(os.path.join(student, CH1)), read(os.path.join(student, CH2))
        self.assertIn('Exercise ex-2.1 is not done yet', ch2)
        self.assertIn('Exercise ex-1.2 comes with a later assignment', ch1)
        self.assertNotIn('Exercise ex-1.1 is not done yet', ch1)
        self.assertIn(read(os.path.join(FIXTURE, CH1)).split('<<Add up the squares of v>>=')[1]
                      .split('@\n')[0], ch1)
        for name in (CH1, CH2):
            self.assertEqual(read(os.path.join(self.out, 'solution', name)),
                             read(os.path.join(FIXTURE, name)))
        self.assertIn('ex-1.2 are stubs too', read(os.path.join(student, 'README.md')))
        self.assertEqual(leaks.find(self.out, FIXTURE), [])

    def test_manifest_has_the_plans_points(self):
        manifest = json.loads(read(os.path.join(self.out, 'student', 'exercises.json')))
        self.assertEqual([(e['id'], e['points']) for e in manifest['exercises']],
                         [('ex-2.1', 10)])
        self.assertEqual(manifest['points'], 10)
        self.assertEqual(manifest['unreleased'], ['ex-1.2'])
        self.assertEqual(manifest['assignment']['name'], 'first')
        readme = read(os.path.join(self.out, 'student', 'README.md'))
        self.assertIn('| 2.1 | 10 | The mean |', readme)

    def test_planted_solution_of_a_later_assignment_is_found(self):
        out = os.path.join(self.tmp, 'planted')
        shutil.copytree(os.path.join(self.out, 'student'), os.path.join(out, 'student'))
        solution = read(os.path.join(FIXTURE, CH1)).split('<<Clamp v to the range>>=')[1]
        solution = solution.split('// BEGIN SOLUTION\n')[1].split('// END SOLUTION')[0]
        path = os.path.join(out, 'student', 'tests', 'ch01', 'test_sums.cpp')
        write(path, read(path) + '/*\n' + solution + '*/\n')
        self.assertTrue([p for p in leaks.find(out, FIXTURE) if 'ex-1.2' in p])

    def test_bad_plan_stops_the_build_with_file_and_line(self):
        bad = os.path.join(self.tmp, 'bad.toml')
        write(bad, self.PLAN.replace('"ex-1.2"]', '"ex-1.3"]'))
        result = run(['python3', os.path.join(TOOLS, 'exercises', 'kits.py'), 'build',
                      '--src', FIXTURE, '--out', os.path.join(self.tmp, 'bad'), '--no-book',
                      '--plan', bad, '--assignment', 'first'])
        self.assertNotEqual(result.returncode, 0)
        self.assertIn(bad + ':10: assignment \'second\': ex-1.3 is not an exercise',
                      result.stderr)

    def test_tests_reaching_a_later_assignments_stub_are_skipped(self):
        # Two tests of ex-1.1, which no assignment sets (so it is solved in the
        # kit), use ex-1.2, which the next assignment sets: one through an
        # exercise call, one in its own check. In the student kit's make test
        # both are skipped with the stub's message, as is ex-1.2's own test;
        # ex-2.1's tests (this assignment's) still fail.
        v = Variant(self)
        v.replace('tests/ch01/exercise_calls.h', 'inline int Clamp(',
                  'inline long SumOfClampedSquares(std::vector<int> v) {\n'
                  '    for (int &x : v) x = lrt::Clamp(x, -3, 3);\n'
                  '    return lrt::SumOfSquares(v);\n}\ninline int Clamp(')
        v.replace('tests/ch01/exercise_calls.h', 'LRT_EXERCISE_CALL(Clamp)',
                  'LRT_EXERCISE_CALL(Clamp)\nLRT_EXERCISE_CALL(SumOfClampedSquares)')
        v.replace('tests/ch01/test_sums.cpp', 'TEST(SumOfSquares, EmptyVectorThrows)',
                  'EXERCISE_TEST(Ex1_1_SumOfSquares, ClampedThroughACall) {\n'
                  '    EXPECT_EQ(ex::SumOfClampedSquares(std::vector<int>{5, -1}), 10);\n}\n\n'
                  'EXERCISE_TEST(Ex1_1_SumOfSquares, ClampedInTheCheck) {\n'
                  '    EXPECT_EQ(ex::SumOfSquares(std::vector<int>{2}), Clamp(9, 0, 4));\n}\n\n'
                  'TEST(SumOfSquares, EmptyVectorThrows)')
        out = os.path.join(self.tmp, 'reaching')
        result = run(['python3', os.path.join(TOOLS, 'exercises', 'kits.py'), 'build', '--src',
                      v.dir, '--out', out, '--no-book', '--plan', self.plan,
                      '--assignment', 'first'])
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        student = os.path.join(out, 'student')
        ch1 = kit_common.make(student, ['test', 'CH=01'])
        self.assertEqual(ch1.returncode, 0, ch1.stdout + ch1.stderr)
        later = ': Exercise ex-1.2 comes with a later assignment: leave <Clamp v to the range>'
        for name in ('Ex1_1_SumOfSquares.ClampedThroughACall',
                     'Ex1_1_SumOfSquares.ClampedInTheCheck', 'Ex1_2_Clamp.InsideAndOutside'):
            self.assertIn('SKIPPED: asof01/ch01 %s%s' % (name, later), ch1.stdout)
        self.assertIn('tests: 4 passed, 0 failed, 3 skipped', ch1.stdout)
        ch2 = kit_common.make(student, ['test', 'CH=02'])
        self.assertNotEqual(ch2.returncode, 0)
        self.assertIn('FAILED: asof02/ch02 Ex2_1_Mean.SmallVectors', ch2.stdout)
        self.assertNotIn('SKIPPED', ch2.stdout)
        # `try` accepts both: the failures are this assignment's, the skips
        # a later one's.
        tried = run(['python3', os.path.join(TOOLS, 'exercises', 'kits.py'), 'try', '--src',
                     v.dir, '--out', out, 'CH=02'])
        self.assertEqual(tried.returncode, 0, tried.stdout + tried.stderr)
        self.assertIn('try: student kit: make test CH=02: tests: 2 passed, 1 failed',
                      tried.stdout)
        # A test of chapter 2 that fails for another reason, and one that
        # reaches ex-2.1's stub: only the first is a problem.
        test = os.path.join(student, 'tests', 'ch02', 'test_means.cpp')
        write(test, read(test) + '\nTEST(Mean, Planted) { EXPECT_EQ(Twice(2), 5); }\n'
              'TEST(Mean, UsesTheMean) { EXPECT_EQ(Mean({2}), 2); }\n')
        tried = run(['python3', os.path.join(TOOLS, 'exercises', 'kits.py'), 'try', '--src',
                     v.dir, '--out', out, 'CH=02'])
        self.assertNotEqual(tried.returncode, 0)
        self.assertIn('student: asof02/ch02 Mean.Planted fails, and not only because of '
                      'this assignment\'s stubs', tried.stderr)
        self.assertNotIn('UsesTheMean fails', tried.stderr)
        # The solution kit must be the source's.
        write(os.path.join(out, 'solution', 'tests', 'ch01', 'test_sums.cpp'), '\n')
        tried = run(['python3', os.path.join(TOOLS, 'exercises', 'kits.py'), 'try', '--src',
                     v.dir, '--out', out, 'CH=01'])
        self.assertIn('solution: tests/ch01/test_sums.cpp is not the source\'s', tried.stderr)


class ValidationTest(unittest.TestCase):
    def test_a_stub_that_passes_its_tests_is_caught(self):
        # Exercise 1.2's stub block holds the solution, so its tests pass in the
        # student edition; exercise 1.1 is fine.
        v = Variant(self).replace(CH1, '(void)v;\n// NOT IMPLEMENTED\n',
                                  'return v < lo ? lo : (v > hi ? hi : v);\n')
        out = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, out)
        build_kits(self, v.dir, out, ['01'])
        result = run(['python3', os.path.join(TOOLS, 'exercises', 'kits.py'), 'validate',
                      '--out', out])
        self.assertNotEqual(result.returncode, 0)
        self.assertRegex(result.stdout, r'solution edition: 7 test runs, 7 passed, 0 failed')
        self.assertRegex(result.stdout, r'student edition: 7 test runs, 4 passed, 3 failed')
        problems = [l for l in result.stderr.splitlines() if l.startswith('student:')]
        self.assertEqual(len(problems), 2, result.stderr)
        self.assertIn('Ex1_2_Clamp.InsideAndOutside passes with the stub of ex-1.2',
                      problems[0])
        self.assertIn('Ex1_2_ClampHidden.RangeOfOneValue passes with the stub of ex-1.2',
                      problems[1])
        self.assertIn('validation failed (2 problems)', result.stderr)


    def test_the_fixture_validates_in_the_kits_and_in_grading(self):
        out = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, out)
        build_kits(self, FIXTURE, out)
        result = run(['python3', os.path.join(TOOLS, 'exercises', 'kits.py'), 'validate',
                      '--out', out])
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        # Graded: each chapter solved, then each exercise alone stubbed.
        self.assertRegex(result.stdout, r'grading: 19 test runs, 12 passed, 7 failed')
        self.assertIn('in the kits and in grading, one exercise stubbed at a time',
                      result.stdout)

    def test_a_test_that_bypasses_the_calls_is_caught(self):
        # Ex1_2_Clamp calls Clamp() itself instead of through its exercise
        # call. In make test that still reaches the student's code, so the
        # kits' validation cannot tell; grading would check the book's code
        # instead, and only the grading validation sees it.
        v = Variant(self).replace('tests/ch01/test_sums.cpp', 'EXPECT_EQ(ex::Clamp(5, 0, 10), 5);',
                                  'EXPECT_EQ(Clamp(5, 0, 10), 5);')
        v.replace('tests/ch01/test_sums.cpp', 'EXPECT_EQ(ex::Clamp(-5, 0, 10), 0);',
                  'EXPECT_EQ(Clamp(-5, 0, 10), 0);')
        v.replace('tests/ch01/test_sums.cpp', 'EXPECT_EQ(ex::Clamp(15, 0, 10), 10);',
                  'EXPECT_EQ(Clamp(15, 0, 10), 10);')
        out = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, out)
        build_kits(self, v.dir, out, ['01'])
        result = run(['python3', os.path.join(TOOLS, 'exercises', 'kits.py'), 'validate',
                      '--out', out])
        self.assertNotEqual(result.returncode, 0)
        self.assertRegex(result.stdout, r'student edition: \d+ test runs')
        self.assertIn('grading with ex-1.2 stubbed: Ex1_2_Clamp.InsideAndOutside passes with '
                      'the stub', result.stderr)


if __name__ == '__main__':
    unittest.main()
