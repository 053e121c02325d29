"""Tests of the book's apparatus in both editions: the numbers of exercises,
cross-references to them and several references in one citation, and the
Index of Identifiers when one name stands for several identifiers.

The fixture book under apparatus/ is woven as the PDF is (exercises.lua then
weave.lua, and pdflatex by weave.sh, whose numbers of sections and equations
are LaTeX's own, read back from the PDF with pdftotext) and as the web
edition is (exercises.lua then html.lua, read back as the text of the HTML).
"""
import html
import os
import re
import shutil
import subprocess
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
BOOK = os.path.join(HERE, 'apparatus')
FILTERS = os.path.join(ROOT, 'tools', 'book')
CHAPTERS = ['01-numbers.md', '02-nodes.md', '03-axes.md']


def run(cmd, cwd=ROOT):
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)


def copy_book(tmp, edit=None):
    """The fixture in tmp, with edit(name, text) -> text applied to each chapter."""
    shutil.copy(os.path.join(BOOK, 'book.md'), tmp)
    paths = []
    for name in CHAPTERS:
        with open(os.path.join(BOOK, 'chapters', name)) as f:
            text = f.read()
        path = os.path.join(tmp, name)
        with open(path, 'w') as f:
            f.write(edit(name, text) if edit else text)
        paths.append(path)
    return [os.path.join(tmp, 'book.md')] + paths


def pandoc(paths, edition):
    last = 'weave.lua' if edition == 'latex' else 'html.lua'
    return run(['pandoc'] + paths + ['--from', 'markdown', '--lua-filter',
                                     os.path.join(FILTERS, 'exercises.lua'), '--lua-filter',
                                     os.path.join(FILTERS, last), '--top-level-division=chapter',
                                     '--mathjax', '-t', 'latex' if edition == 'latex' else 'html5'])


def words(text):
    return re.sub(r'\s+', ' ', text.replace('\u00a0', ' ')).strip()


def html_text(markup):
    return words(html.unescape(re.sub(r'<[^>]*>', '', markup)))


class Woven(unittest.TestCase):
    """The fixture woven once in each edition (and as a PDF)."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp()
        paths = copy_book(cls.tmp)
        cls.latex = pandoc(paths, 'latex')
        cls.html = pandoc(paths, 'html')
        out = os.path.join(cls.tmp, 'out')
        cls.weave = run([os.path.join(FILTERS, 'weave.sh'), out] + paths)
        cls.pdf_text = words(run(['pdftotext', os.path.join(out, 'book.pdf'), '-']).stdout) \
            if cls.weave.returncode == 0 else ''

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp)

    def setUp(self):
        for result in (self.latex, self.html, self.weave):
            self.assertEqual(result.returncode, 0, result.stderr)

    def assertInBoth(self, text):
        self.assertIn(text, self.pdf_text)
        self.assertIn(text, html_text(self.html.stdout))


class ExerciseNumbersTest(Woven):
    def test_exercises_of_a_chapter_are_numbered_in_order_graded_or_not(self):
        # Chapter 1: two ungraded, then ex-1.3; chapter 2: ex-2.1, then one ungraded.
        for shown in ('1.1 Counting. Count the equations', '1.2 Adding. Add them.',
                      'Exercise 1.3 Graded', 'Exercise 2.1 Graded first',
                      '2.2 Later. An exercise after a graded one.'):
            self.assertInBoth(shown)
        self.assertIn('\\phantomsection\\label{ex:counting}\\textbf{1.1} \\emph{Counting.}',
                      self.latex.stdout)
        self.assertIn('<span id="ex:later" class="problem"><strong>2.2</strong>',
                      self.html.stdout)

    def test_references_to_exercises(self):
        self.assertInBoth('One: Exercise 1.1.')
        self.assertInBoth('Three exercises: Exercises 1.1\u20131.3.')
        self.assertInBoth('Two exercises: Exercises 1.1 and 1.2.')
        self.assertInBoth('Next chapter: Exercise 2.2 and Exercises 2.1 and 2.2.')
        self.assertIn('\\hyperref[ex:counting]{Exercise~1.1}', self.latex.stdout)
        self.assertIn('<a href="#ex-1.3">1.3</a>', self.html.stdout)


class ExerciseNumberErrorsTest(unittest.TestCase):
    def weave(self, edit, edition='latex'):
        tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, tmp)
        return pandoc(copy_book(tmp, edit), edition), tmp

    def line_of(self, name, text):
        with open(os.path.join(BOOK, 'chapters', name)) as f:
            for number, line in enumerate(f, 1):
                if text in line:
                    return number

    def test_a_graded_id_that_disagrees_with_its_number_fails_at_its_line(self):
        line = self.line_of('01-numbers.md', '#ex-1.3 ')
        for edition in ('latex', 'html'):
            result, tmp = self.weave(lambda name, text: text.replace('#ex-1.3 ', '#ex-1.4 '),
                                     edition)
            self.assertNotEqual(result.returncode, 0)
            self.assertIn('%s:%d: the exercise ex-1.4 is exercise 1.3 of its chapter'
                          % (os.path.join(tmp, '01-numbers.md'), line), result.stderr)

    def test_an_exercise_added_before_a_graded_one_shifts_its_number_and_fails(self):
        line = self.line_of('02-nodes.md', '#ex-2.1 ')
        result, tmp = self.weave(lambda name, text: text.replace(
            '## Exercises {#sec:exercises-2}\n',
            '## Exercises {#sec:exercises-2}\n\n[New.]{.problem #ex:new} A new one.\n'))
        self.assertNotEqual(result.returncode, 0)
        self.assertIn('%s:%d: the exercise ex-2.1 is exercise 2.2 of its chapter'
                      % (os.path.join(tmp, '02-nodes.md'), line + 2), result.stderr)

    def test_an_ungraded_exercise_without_an_id_fails_at_its_line(self):
        line = self.line_of('01-numbers.md', '{.problem #ex:adding}')
        result, tmp = self.weave(lambda name, text: text.replace(' #ex:adding', ''))
        self.assertNotEqual(result.returncode, 0)
        self.assertIn('%s:%d: the exercise "Adding." needs an id'
                      % (os.path.join(tmp, '01-numbers.md'), line), result.stderr)


class GroupedReferencesTest(Woven):
    def test_several_references_in_one_citation_read_as_prose(self):
        self.assertInBoth('Pair: Equations (1.1) and (1.2).')
        self.assertInBoth('Triple: Equations (1.1), (1.2) and (1.3).')
        self.assertInBoth('Run: Sections 1.2\u20131.4.')
        self.assertInBoth('Apart: Sections 1.1 and 1.3.')
        # Two fourth-level headings of one section show its number once.
        self.assertInBoth('Details: Section 1.2.')

    def test_a_bare_reference_shows_the_number_alone(self):
        self.assertInBoth('Bare: the implicit equation (1.2).')
        self.assertInBoth('Bare pair: the forms (1.1) and (1.3).')

    def test_each_number_is_a_link(self):
        self.assertIn('Equations~\\hyperref[eq:one]{(\\ref*{eq:one})} and\n'
                      '\\hyperref[eq:two]{(\\ref*{eq:two})}', self.latex.stdout)
        self.assertIn('Sections <a href="#sec:second">1.2</a>\u2013<a href="#sec:fourth">1.4</a>',
                      self.html.stdout.replace('\u00a0', ' '))

    def test_a_citation_of_two_kinds_fails(self):
        tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, tmp)
        result = pandoc(copy_book(tmp, lambda name, text: text.replace(
            'Pair: [@eq:one; @eq:two]', 'Pair: [@eq:one; @sec:first]')), 'latex')
        self.assertNotEqual(result.returncode, 0)
        self.assertIn('mixes kinds (Equation, Section)', result.stderr)


class IdentifierIndexTest(Woven):
    """`axis` is a local of chapter 1 that no chunk defines, a member of Node
    in chapter 2 (used before and after its definition) and a function of
    chapter 3: two identifiers in the index, and chapter 1's word in
    neither."""

    def test_each_identifier_of_a_name_collects_its_own_uses(self):
        entries = re.findall(r'\\identindexentry\{axis\}.*', self.latex.stdout)
        self.assertEqual(entries, [
            '\\identindexentry{axis}{\\chunkref{chunk:2.2}{2.2}}{used in '
            '\\chunkref{chunk:2.1}{2.1}, \\chunkref{chunk:2.3}{2.3}}',
            '\\identindexentry{axis}{\\chunkref{chunk:3.1}{3.1}}{used in '
            '\\chunkref{chunk:3.2}{3.2}}'])

    def test_the_web_index_and_footers_link_the_right_identifier(self):
        items = re.findall(r'<li id="(ident-axis[^"]*)">(.*?)</li>', self.html.stdout)
        self.assertEqual([(anchor, html_text(body)) for anchor, body in items],
                         [('ident-axis', 'axis 2.2; used in 2.1, 2.3'),
                          ('ident-axis--3', 'axis 3.1; used in 3.2')])
        # The footer of chunk 3.1 (which defines axis) links to the second.
        footer = re.search(r'id="chunk:3\.1".*?<div class="fragfoot">(.*?)</div>',
                           self.html.stdout, re.S).group(1)
        self.assertIn('href="#ident-axis--3"', footer)


if __name__ == '__main__':
    unittest.main()
