"""Tests of the toolchain itself: the lint's messages, the tangle's line
directives, and the weave filter's cross-check against noweb.

Each broken chapter under lint/ shows one mistake; its test asserts the exact
file:line the lint names, so a message that drifts or points nowhere fails.
"""
import os
import shutil
import subprocess
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
TOOLS = os.path.join(ROOT, 'tools')
LINT_CASES = os.path.join(HERE, 'lint')


def run(cmd, cwd=ROOT):
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)


def lint(*names):
    return run(['python3', os.path.join(TOOLS, 'lint.py')] +
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
        # The reference back to the first chapter is fine.
        self.assertNotIn('forward-ref-b.md:5',
                         lint('forward-ref-a.md', 'forward-ref-b.md').stderr)

    def test_chunk_outside_a_fence(self):
        self.assertLintError(['chunk-in-list.md'], 'chunk-in-list.md:4',
                             ['must follow a ```cpp fence'])

    def test_code_wider_than_the_column(self):
        self.assertLintError(['long-line.md'], 'long-line.md:5', ['columns'])

    def test_chapter_names_the_build_can_order(self):
        result = run(['python3', os.path.join(TOOLS, 'lint.py'), '--book',
                      'tests/tools/lint/good.md'])
        self.assertEqual(result.returncode, 1)
        self.assertIn('tests/tools/lint/good.md:0: a chapter file is named NN-slug.md',
                      result.stderr)

    def test_missing_chapter_file(self):
        self.assertLintError(['no-such-chapter.md'], 'no-such-chapter.md:0',
                             ['cannot read chapter'])


class TangleTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, self.tmp)

    def tangle(self, *args):
        return run(['python3', os.path.join(TOOLS, 'tangle.py')] + list(args))

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

    def test_undefined_fragment_fails_the_tangle(self):
        result = self.tangle('--out', os.path.join(self.tmp, 'out'),
                             os.path.join(LINT_CASES, 'undefined-use.md'))
        self.assertNotEqual(result.returncode, 0)
        self.assertIn('Body of f', result.stderr)


class WeaveTest(unittest.TestCase):
    """The filter's own reading of the chunks must match noweb's."""

    def weave(self, text):
        tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, tmp)
        chapter = os.path.join(tmp, '01-weave.md')
        with open(chapter, 'w') as f:
            f.write(text)
        return run(['pandoc', chapter, '--lua-filter', os.path.join(TOOLS, 'weave.lua'),
                    '-t', 'latex'])

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


if __name__ == '__main__':
    unittest.main()
