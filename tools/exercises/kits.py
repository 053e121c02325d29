#!/usr/bin/env python3
"""Student and solution kits of the exercises; the command line of their
leak check, validation and try.

    tools/exercises/kits.py build --out DIR [--src DIR] [--no-book] [NN ...]
    tools/exercises/kits.py leaks --out DIR [--src DIR]
    tools/exercises/kits.py validate --out DIR [--edition student|solution]
    tools/exercises/kits.py try --out DIR [--src DIR] [MAKE_ARG ...]

build: DIR/student/ and DIR/solution/ (and DIR/lrt-student.tar.gz,
DIR/lrt-solution.tar.gz) for the exercises of chapters NN (all chapters when
none is given). A kit holds chapters 1 to the last chosen one: the chosen
chapters with stubs in place of solutions (student kit), the other chapters
as they are; the public tests of those chapters; the Makefile, tools/ and
tests/tools/ of this repository; book.md, figures/, data/; a README; the book
as book.pdf and as web pages in html/ (open html/index.html), and the readable
tangle in tangled/ (all built in the kit); exercises.json. The solution kit
adds tests/hidden/. The student kit must pass the leak check, which `build`
runs last.

leaks: the leak check of the student kit (tools/exercises/leaks.py).
validate: both kits' tests, and grading in the solution kit
(tools/exercises/validate.py).
try: the kits as their readers use them (tools/exercises/try_kits.py).

--src is where chapters/, tests/, book.md, figures/ and data/ come from (the
repository by default); the Makefile, tools/ and tests/tools/ always come from
the repository that holds this script.
"""
import argparse
import json
import os
import re
import shutil
import sys
import tarfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(os.path.dirname(HERE)))  # the repository: import tools.*
from tools.exercises import course  # noqa: E402
from tools.exercises import leaks  # noqa: E402
from tools.exercises import markup  # noqa: E402
from tools.exercises import try_kits  # noqa: E402
from tools.exercises import validate  # noqa: E402
from tools.exercises.kit_common import (EDITIONS, ROOT, fail, make, shown,  # noqa: E402
                                        source_book, stop_on)

# The toolchain's own tests go into every kit (the kit's `make test` runs
# them) except the exercise machinery's, whose fixtures hold solutions, and
# the grader's and the autograder's, which grade the repository's own
# solutions with its hidden tests: in a student kit, whose chapters hold
# stubs, they could only fail. The web edition's are left out too: they open
# pages of chapter 5, which a kit of the first chapters lacks, and a
# student's machine may have no browser. The house's checks read the
# repository's maps (README.md, docs/), which a kit replaces by its own README.
TOOL_TESTS_LEFT_OUT = ('exercises', 'test_exercises.py', 'test_grade.py', 'attacks.py',
                       'test_grade_batch.py', 'test_grade_crash.py', 'test_grade_limits.py',
                       'test_compile_wall.py', 'test_grade_hidden.py', 'test_grade_wall.py',
                       'test_gradescope.py', 'test_html.py', 'test_house.py', '__pycache__')


def selection(book, wanted):
    numbers = [c.number for c in book.chapters]
    if not wanted:
        return numbers
    chosen = []
    for word in wanted:
        match = re.match(r'^(?:.*/)?(\d{1,2})(?:-.*\.md)?$', word)
        if not match:
            fail('CHAPTERS names chapters by number ("03 05"), not %r' % word)
        number = '%02d' % int(match.group(1))
        if number not in numbers:
            fail('there is no chapter %s (chapters: %s)' % (number, ' '.join(numbers)))
        chosen.append(number)
    return sorted(set(chosen))


# ---------------------------------------------------------------------------
# Building the kits

def copy_tree(source, target, leave_out=('__pycache__',)):
    if os.path.isdir(source):
        shutil.copytree(source, target, ignore=shutil.ignore_patterns(*leave_out))


def copy_file(source, target):
    if os.path.isfile(source):
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copy2(source, target)


class Choice:
    """What a pair of kits is for: the chapters given by number (every
    exercise of them), or one assignment of a course plan (docs/course.md).

    numbers: the chapters whose exercises are chosen (the kit holds chapters
    1 to the last of them); chosen: those exercises (Exercise objects);
    points: {id: points}, the plan's where it says; stubbed: the exercises
    that are stubs in the student kit: the chosen ones, and with a plan also
    those of the assignments released later (earlier chapters' included), so
    that no solution is handed out before its assignment."""

    def __init__(self, book, chapters=None, plan=None, assignment=None):
        self.plan, self.assignment = plan, None
        if plan is None:
            if assignment:
                fail('ASSIGNMENT needs PLAN (a course plan, docs/course.md)')
            self.numbers = selection(book, chapters)
            self.chosen = [e for e in book.exercises if e.chapter in self.numbers]
            self.points = {e.id: e.points for e in self.chosen}
            self.stubbed = {e.id for e in self.chosen}
            self.later = set()
            return
        if chapters:
            fail('give CHAPTERS or PLAN, not both')
        if not assignment:
            fail('PLAN needs ASSIGNMENT: the kits are those of one assignment')
        try:
            loaded = course.load(plan, {e.id: e.points for e in book.exercises})
            self.assignment = loaded.assignment(assignment)
        except course.PlanError as e:
            fail(str(e))
        ids = self.assignment.exercises
        self.chosen = [e for e in book.exercises if e.id in ids]
        self.numbers = sorted({e.chapter for e in self.chosen})
        self.points = dict(self.assignment.points)
        self.later = set(loaded.unreleased(assignment)) - set(ids)
        self.stubbed = set(ids) | self.later

    def manifest(self):
        if self.assignment is None:
            return {}
        a = self.assignment.as_dict()
        a['plan'] = os.path.basename(self.plan)
        return {'assignment': a, 'unreleased': sorted(self.later)}


def exercise_table(chosen, points):
    if not chosen:
        return 'This set has no exercises.'
    rows = ['| exercise | points | title | chapter file | section | tests |',
            '|---|---|---|---|---|---|']
    for e in chosen:
        section = e.section.label() if e.section.number else e.section.title
        rows.append('| %s | %g | %s | `%s` | %s | `%s*` |' % (
            e.number, points[e.id], e.title, e.path, section, e.suite_prefix))
    rows.append('')
    rows.append('%d exercises, %g points in all.' % (len(chosen),
                                                     sum(points[e.id] for e in chosen)))
    return '\n'.join(rows)


def later_note(book, choice):
    """For the kit of an assignment of a plan: the stubs of exercises that
    later assignments set, which are not this one's to write."""
    last = max(choice.numbers)
    later = [e for e in book.exercises if e.id in choice.later and e.chapter <= last]
    if not later:
        return ''
    return ('\n\nThe exercises %s are stubs too: a later assignment sets them, and '
            'their stubs say so. `make test` skips every test that reaches one of '
            'them, naming the exercise, instead of failing it; leave them for now.'
            % ', '.join(e.id for e in later))


def readme(edition, book, kit_chapters, choice):
    chosen_numbers, chosen = choice.numbers, choice.chosen
    with open(os.path.join(HERE, 'kit', 'README.%s.md' % edition), encoding='utf-8') as f:
        text = f.read()
    example = chosen[0] if chosen else None
    first, last = int(kit_chapters[0].number), int(kit_chapters[-1].number)
    values = {
        'CHAPTER_RANGE': '%d to %d' % (first, last) if first != last else str(first),
        'SELECTED': ', '.join(str(int(n)) for n in chosen_numbers
                              if not chosen or any(e.chapter == n for e in chosen)),
        'SELECTED_FILES': ', '.join('`%s`' % c.path for c in kit_chapters
                                    if c.number in chosen_numbers),
        'EXERCISES': exercise_table(chosen, choice.points),
        'LATER': later_note(book, choice),
        'EXAMPLE_ID': example.id if example else 'ex-N.K',
        'EXAMPLE_CH': example.chapter if example else 'NN',
        'EXAMPLE_N': str(int(example.chapter)) if example else 'N',
        'EXAMPLE_NUMBER': example.number if example else 'N.K',
        'EXAMPLE_FILTER': (example.suite_prefix + '*') if example else 'ExN_K_*',
        'EXAMPLE_FILE': os.path.basename(example.path) if example else 'NN-slug.md',
    }
    for key, value in values.items():
        text = text.replace('{{%s}}' % key, value)
    return text


def write_kit(edition, src, out, book, choice, build_book):
    kit = os.path.join(out, edition)
    if os.path.exists(kit):
        shutil.rmtree(kit)
    os.makedirs(kit)
    chosen_numbers, chosen = choice.numbers, choice.chosen
    last = max(chosen_numbers)
    kit_chapters = [c for c in book.chapters if c.number <= last]

    copy_file(os.path.join(ROOT, 'Makefile'), os.path.join(kit, 'Makefile'))
    copy_tree(os.path.join(ROOT, 'tools'), os.path.join(kit, 'tools'))
    copy_tree(os.path.join(ROOT, 'tests', 'tools'), os.path.join(kit, 'tests', 'tools'),
              TOOL_TESTS_LEFT_OUT)
    for name in ('book.md', 'references.bib', 'LICENSE', '.gitignore'):
        copy_file(os.path.join(src, name), os.path.join(kit, name))
    for name in ('figures', 'data'):
        copy_tree(os.path.join(src, name), os.path.join(kit, name))
    # The exercise calls' framework is tooling, like tools/.
    copy_tree(os.path.join(ROOT, 'tests', 'calls'), os.path.join(kit, 'tests', 'calls'))
    for chapter in kit_chapters:
        target = os.path.join(kit, chapter.path)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        stubbed = [e for e in chapter.exercises if e.id in choice.stubbed]
        if edition == 'student' and stubbed:
            lines = markup.student_edition(chapter, only=stubbed, later=choice.later)
        else:
            lines = chapter.lines
        with open(target, 'w', encoding='utf-8') as f:
            f.write('\n'.join(lines))
        copy_tree(os.path.join(src, 'tests', 'ch' + chapter.number),
                  os.path.join(kit, 'tests', 'ch' + chapter.number))
        if edition == 'solution':
            copy_tree(os.path.join(src, 'tests', 'hidden', 'ch' + chapter.number),
                      os.path.join(kit, 'tests', 'hidden', 'ch' + chapter.number))
    with open(os.path.join(kit, 'README.md'), 'w', encoding='utf-8') as f:
        f.write(readme(edition, book, kit_chapters, choice))
    listed = [e.as_dict(hidden=edition == 'solution') for e in chosen]
    for e in listed:
        e['points'] = choice.points[e['id']]
    manifest = {
        'edition': edition,
        'chapters': [c.path for c in kit_chapters],
        'chosen_chapters': chosen_numbers,
        'exercises': listed,
        'points': sum(choice.points.values()),
    }
    manifest.update(choice.manifest())
    with open(os.path.join(kit, 'exercises.json'), 'w', encoding='utf-8') as f:
        json.dump(manifest, f, indent=2)
        f.write('\n')

    # The kit is built with its own Makefile, as its README tells the reader
    # to (`make`: the tangle, the library, the book; and the web edition), so
    # a kit whose `make` fails is never handed out. The two kits share the
    # web edition's compiled drawings.
    proc = make(kit, ['all', 'html', 'HTML_CACHE=' + os.path.join(out, 'html-cache')]
                if build_book else ['tangle'])
    if proc.returncode != 0:
        fail('%s kit: make failed in %s:\n%s%s' % (edition, kit, proc.stdout[-3000:],
                                                   proc.stderr[-3000:]))
    if build_book:
        shutil.copy2(os.path.join(kit, 'build', 'book.pdf'), os.path.join(kit, 'book.pdf'))
        shutil.copytree(os.path.join(kit, 'build', 'html'), os.path.join(kit, 'html'))
    shutil.rmtree(os.path.join(kit, 'build'), ignore_errors=True)
    if os.path.exists(os.path.join(kit, 'compile_commands.json')):
        os.remove(os.path.join(kit, 'compile_commands.json'))
    return kit, chosen


def tarball(out, edition):
    path = os.path.join(out, 'lrt-%s.tar.gz' % edition)
    kit = os.path.join(out, edition)
    with tarfile.open(path, 'w:gz') as tar:
        for top, dirs, files in os.walk(kit):
            dirs.sort()
            for name in sorted(files):
                full = os.path.join(top, name)
                tar.add(full, arcname=os.path.join('lrt-' + edition,
                                                   os.path.relpath(full, kit)))
    return path


def build(args):
    src = os.path.abspath(args.src)
    book = source_book(src)
    choice = Choice(book, args.chapters, args.plan and os.path.abspath(args.plan),
                    args.assignment)
    chosen_numbers = choice.numbers
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    for edition in EDITIONS:
        started = time.time()
        kit, chosen = write_kit(edition, src, out, book, choice, not args.no_book)
        path = tarball(out, edition)
        print('exercises: %s kit in %s, %s (%.0f s)' % (edition, shown(kit), shown(path),
                                                         time.time() - started))
    if choice.assignment:
        print('  assignment %s of %s' % (choice.assignment.name, shown(choice.plan)))
    for e in chosen:
        print('  %-8s %2g points  %s' % (e.id, choice.points[e.id], e.title))
    print('  %d exercises, %g points, chapters %s' % (
        len(chosen), sum(choice.points.values()), ' '.join(chosen_numbers)))
    later = sorted(choice.stubbed - set(choice.points))
    if later:
        print('  stubs also for the exercises of later assignments: %s' % ' '.join(later))
    stop_on(leaks.find(out, src), 'the student kit leaks solutions or hidden tests (%d findings)')
    print('exercises: leak check passed: no solution line or hidden test name in the '
          'student kit, its tangle, its book, its web pages or its tarball')


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    sub = parser.add_subparsers(dest='command', required=True)
    p = sub.add_parser('build')
    p.add_argument('--out', required=True)
    p.add_argument('--src', default=ROOT)
    p.add_argument('--no-book', action='store_true',
                   help='build neither book.pdf nor the web pages (html/)')
    p.add_argument('--plan', help='a course plan (docs/course.md)')
    p.add_argument('--assignment', help='with --plan: the kits of this assignment')
    p.add_argument('chapters', nargs='*')
    p = sub.add_parser('leaks')
    p.add_argument('--out', required=True)
    p.add_argument('--src', default=ROOT)
    p.add_argument('--edition', default='student', choices=EDITIONS)
    p = sub.add_parser('try')
    p.add_argument('--out', required=True)
    p.add_argument('--src', default=ROOT)
    p.add_argument('make_args', nargs='*', metavar='MAKE_ARG',
                   help='for the kits\' make test, e.g. UPTO=last')
    p = sub.add_parser('validate')
    p.add_argument('--out', required=True)
    p.add_argument('--edition', action='append', choices=validate.VALIDATIONS)
    p.add_argument('--jobs', type=int, default=os.cpu_count() or 1)
    args = parser.parse_args(argv)
    {'build': build, 'leaks': leaks.command, 'validate': validate.command,
     'try': try_kits.command}[args.command](args)


if __name__ == '__main__':
    main()
