#!/usr/bin/env python3
"""Grade a student's submission with lrt's tests (docs/grading.md).

    tools/grading/grade.py [options] SUBMISSION          grade one submission
    tools/grading/grade.py --batch DIR [--out DIR]       grade every submission in DIR

A submission is a directory, a .tar.gz/.tgz or a .zip holding edited chapter
files: chapters/NN-slug.md, or NN-slug.md anywhere in it (submission.py).
Which chapters and exercises are graded (selection.py): those of --chapters
("05", "02 05"), else the chapters a kit was built for (its exercises.json),
else every chapter with exercises; with --plan FILE --assignment NAME (a
course plan, docs/course.md), the assignment's exercises, worth the plan's
points. @FILE stands for the arguments in FILE, one per line (Gradescope's
grade_flags). A graded chapter missing from the submission scores 0.

Each graded chapter is graded exercise by exercise (grade_chapter). The
student's chunks are compared with the book's (structure.py): renamed,
deleted or duplicated exercise chunks and code changed outside the solution
regions are reported at the student's file:line, and the book's code is
used outside the regions unless --allow-changes-outside-exercises. The
text of one exercise (the student's regions for it, the book's solutions
for the others) must pass the compile wall (compile_wall.py: what a region
may hold), is compiled in the sandbox (sandbox.py, build.py) into that
exercise's worker, and a compile error scores the exercise 0 with its first
errors at the student's lines (diagnostics.py). Then the chapter's judge
(tests/calls/judge.cpp: the book's code and tests, which runs none of the
student's code) runs the exercise's public tests, then its hidden ones,
each test in a verdict of its own decided from the worker's answers; the
worker, in the sandbox with a time and a memory limit, runs the student's
code on the arguments of each call (judging.py). The judge's records say
each test's verdict and each failure's kind; text printed by the student's
code counts for nothing. Statuses: PASS, FAIL, CRASH, TIMEOUT, OOM,
COMPILE-ERROR, NOT-RUN. An exercise's points are split evenly over its
tests, public and hidden.

Outputs, in --out (default build/grade/NAME), rewritten atomically after
every exercise (report.py): results.json (Gradescope), junit.xml and
results.txt. --batch DIR grades every submission in DIR (batch.py).
The wall and what each part of it stops: docs/grading.md, "The trust
boundary".
"""
import argparse
import os
import re
import secrets
import shutil
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, ROOT)  # the repository: import tools.*
from tools.exercises import markup  # noqa: E402
from tools.grading import build as grade_build  # noqa: E402
from tools.grading import compile_wall  # noqa: E402
from tools.grading import sandbox  # noqa: E402
from tools.grading.batch import ARCHIVE_SUFFIX, grade_batch, name_problem  # noqa: E402
from tools.grading.diagnostics import compiler_errors, region_lines, shown_output  # noqa: E402
from tools.grading.judging import judge_exercise  # noqa: E402
from tools.grading.report import Report, Result, fence_safe  # noqa: E402
from tools.grading.selection import graded_exercises, hint_text, load_book  # noqa: E402
from tools.grading.structure import check_structure, exercise_text, parse_chapter  # noqa: E402,E501
from tools.grading.submission import printable, read_submission  # noqa: E402

DEFAULT_CXXFLAGS = ' '.join(grade_build.WORKER_CXXFLAGS)  # tools/compile/flags.mk



def structure_note(message):
    """A structure problem as a line of the feedback: in a code span, since
    it quotes the student's chunk names, which may hold Markdown (links,
    images) that the feedback must not render."""
    return '- `%s`' % printable(message.replace('`', "'"))

def grade(args, path, out):
    root = args.root
    ref_paths, book = load_book(root)
    selected = graded_exercises(book, args, root)
    label = re.sub(r'\.(tar\.gz|tgz|zip)$', '', os.path.basename(os.path.normpath(path)))
    report = Report(out, label)
    report.secret = args.secret
    names = {os.path.basename(p): p for p in ref_paths}
    sub = read_submission(path, set(names))
    graded = [c for c in book.chapters if any(e.id in selected for e in c.exercises)]
    # Every graded exercise's tests, NOT-RUN until graded.
    for chapter in graded:
        for e in chapter.exercises:
            if e.id not in selected:
                continue
            points = selected[e.id]
            report.exercises.append((chapter.number, e.id, points))
            tests = [(s, n, False) for s, n, _, _ in sorted(set(e.public_tests))] + \
                    [(s, n, True) for s, n, _, _ in sorted(set(e.hidden_tests))]
            tests = list(dict.fromkeys(tests))
            hint = hint_text(e, chapter.lines)
            stubs = frozenset(markup.stub_message(e, f, later) for f in e.fragments
                              for later in (False, True))
            for s, n, hidden in tests:
                r = Result(e.id, chapter.number, s, n, hidden, points / len(tests), hint)
                r.message = 'chapter %s is not in the submission' % chapter.path
                r.stubs = stubs
                report.results.append(r)
    for problem in sub.problems:
        report.notes.append('- ' + problem)
    for name, reason in sub.ignored:
        report.notes.append('- ignored `%s`: %s' % (name, reason))
    if not sub.chapters:
        report.notes.insert(0, '**No chapter file found in the submission**: expected '
                            'chapters/NN-slug.md files, for example %s.'
                            % ', '.join(c.path for c in graded))
    else:
        report.notes.insert(0, 'Chapters found: %s' % ', '.join(
            '`%s`' % n for n, _ in sub.chapters.values()))
        for base in sorted(sub.chapters):
            chapter = [c for c in book.chapters if os.path.basename(c.path) == base][0]
            if not chapter.exercises:
                report.notes.append('- `%s` has no exercises: not graded'
                                    % sub.chapters[base][0])
            elif chapter not in graded:
                report.notes.append('- `%s`: not graded in this assignment (it grades '
                                    'chapter%s %s)' % (sub.chapters[base][0],
                                                       's' if len(graded) > 1 else '',
                                                       ', '.join(c.number for c in graded)
                                                       or 'none'))
    report.write()
    for chapter in graded:
        base = os.path.basename(chapter.path)
        if base in sub.chapters:
            try:
                grade_chapter(args, book, chapter, sub.chapters[base], ref_paths, report)
            except Exception as e:   # a grader bug costs this chapter, not the others
                report.failed = True
                report.notes.append('**The grader failed on chapter %s** (%s: %s); its tests '
                                    'are NOT-RUN: tell your instructor.'
                                    % (chapter.number, type(e).__name__, e))
                for r in report.results:
                    if r.chapter == chapter.number and r.status == 'NOT-RUN':
                        r.message = 'the grader failed'
                report.write()
    report.write()
    return report


def grade_chapter(args, book, chapter, submitted, ref_paths, report):
    """Grades each exercise of the chapter on its own: its worker holds the
    student's code for that exercise and the book's for every other one, and
    the chapter's judge (the book's code) runs the exercise's tests against it."""
    root = args.root
    number = chapter.number
    student_name, data = submitted
    results = [r for r in report.results if r.chapter == number]
    for r in results:
        r.message = 'not run'
    allow = args.allow_changes_outside_exercises
    with tempfile.TemporaryDirectory(prefix='lrt-grade-') as work:
        student_copy = os.path.join(work, 'student', os.path.basename(chapter.path))
        os.makedirs(os.path.dirname(student_copy))
        with open(student_copy, 'wb') as f:
            f.write(data)
        try:
            data.decode('utf-8')
            student, _ = parse_chapter(student_copy)
            problems, changes, plan = check_structure(chapter, student, student_name, allow)
            notes = []
        except UnicodeDecodeError:
            student, problems, changes, plan = None, [], [], {}
            notes = ['`%s` is not UTF-8 text: every exercise is graded as not done'
                     % student_name]
        if changes and allow:
            notes.append('Code outside the exercises was changed (allowed; graded with '
                         'your code):')
        elif changes:
            notes.append('**Warning**: code outside the exercises was changed; the '
                         'book\'s code is used there instead of yours:')
        notes += [structure_note(p) for p in problems + changes]
        report.notes += ['', '### Chapter %s (`%s`)' % (number, student_name)] + \
            (notes or ['Structure: as in the book.'])
        report.notes.append('Each exercise is built with your code for it and the book\'s '
                            'code for the others, and your code ran %s.'
                            % sandbox.describe())
        report.write()
        judge = grade_build.judge(args.cache, root, number, jobs=args.build_jobs)
        builder = grade_build.WorkerBuild(args.cache, root, number, args.cxxflags.split(),
                                          jobs=args.build_jobs,
                                          time_limit=args.compile_time_limit,
                                          memory_mb=args.memory_limit)
        earlier = [p for p in ref_paths if markup.chapter_number(p) < number]
        # What a diagnostic may not quote: the book's solutions, in the
        # earlier chapters (every exercise's) and in this one (every other
        # exercise's; below).
        book_solution_lines = {c.path: region_lines(c.regions) for c in book.chapters
                               if c.path in earlier}
        for exercise in chapter.exercises:
            mine = [r for r in results if r.exercise == exercise.id]
            if not mine:    # not graded in this assignment
                continue
            if student is None:
                text, line_map = exercise_text(chapter, None, {}, exercise, student_name,
                                               False)
            else:
                text, line_map = exercise_text(chapter, student, plan, exercise,
                                               student_name, allow and bool(changes))
            tree = os.path.join(work, exercise.id)
            os.makedirs(os.path.join(tree, 'chapters'))
            for p in earlier:
                shutil.copy(os.path.join(root, p), os.path.join(tree, p))
            with open(os.path.join(tree, chapter.path), 'w', encoding='utf-8') as f:
                f.write(text)
            files = [os.path.basename(p) for p in earlier + [chapter.path]]

            composed = parse_chapter(os.path.join(tree, chapter.path))[0]
            hidden_lines = dict(book_solution_lines)
            hidden_lines[chapter.path] = region_lines(
                r for r in composed.regions if r.chunk.name not in exercise.fragments)

            def rename(path, line, col, line_map=line_map, hidden_lines=hidden_lines):
                col = ':' + col if col else ''
                m = re.search(r'(chapters/[^/]*)$', path)
                if m and line in hidden_lines.get(m.group(1), ()):
                    return None
                if path.endswith(chapter.path) and 1 <= line <= len(line_map):
                    f, n = line_map[line - 1]
                    return '%s:%d%s' % (f, n, col)
                m = re.search(r'(chapters/.*|tests/.*|lrt/.*)$', path)
                if m and m.group(1).startswith('lrt/'):
                    # The tangle without #line directives: which exercise's
                    # code a line is cannot be told, so none is shown.
                    return None
                if m and m.group(1).startswith('chapters/'):
                    return '%s:%d%s (the book\'s text)' % (m.group(1), line, col)
                return '%s:%d%s' % (m.group(1) if m else os.path.basename(path), line, col)

            refused = compile_wall.check(chapter, composed,
                                         lambda n: '%s:%d' % line_map[n - 1],
                                         set(exercise.fragments))
            if refused:
                for r in mine:
                    r.status = 'COMPILE-ERROR'
                    r.message = '%s is not compiled: %s' % (exercise.id, '\n'.join(refused))
                report.notes += ['', '**%s is not compiled** (its tests score 0): %s:'
                                 % (exercise.id, compile_wall.RULES), '```',
                                 fence_safe('\n'.join(refused)), '```']
                report.write()
                continue
            try:
                worker = builder.build(os.path.join(tree, 'chapters'), files, exercise.id)
            except grade_build.BuildError as e:
                errors = compiler_errors(e.output, rename) or \
                    shown_output(e.output.strip().splitlines()[-10:], rename)
                for r in mine:
                    r.status = 'COMPILE-ERROR'
                    r.message = '%s does not compile: %s' % (exercise.id, '\n'.join(errors))
                report.notes += ['', '**Compile error in %s** (its tests score 0):'
                                 % exercise.id, '```', fence_safe('\n'.join(errors)), '```']
                report.write()
                continue
            judge_exercise(args, judge, worker, mine, args.secret)
            report.write()


def default_out(parser, root, submission):
    """build/grade/NAME for a submission graded alone. NAME comes from the
    submission's path, so it must be a safe name: "..", "." or "" (from
    SUBMISSION=.., ., /, ...tar.gz) would put the results in build/ or
    build/grade/, and "cache" or "batch" among the build cache's or a
    batch's files."""
    label = ARCHIVE_SUFFIX.sub('', os.path.basename(os.path.normpath(submission)))
    problem = name_problem(label) or ('%s is a directory of the grader\'s own' % label
                                      if label.lower() in ('cache', 'batch') else None)
    if problem:
        parser.error('cannot name the results after %s (%s): give --out DIR (OUT= for '
                     'make)' % (printable(submission), problem))
    return os.path.join(root, 'build', 'grade', label)


class FlagsFileParser(argparse.ArgumentParser):
    """@FILE on the command line stands for the arguments in FILE, one per
    line; blank lines and lines that start with # are left out (Gradescope's
    grade_flags, tools/grading/gradescope.py)."""
    def convert_arg_line_to_args(self, line):
        line = line.strip()
        return [] if not line or line.startswith('#') else [line]


def protect_from_the_sandbox(args, submissions, out):
    """Without namespaces, the sandbox's user sees the file system as any
    user does: what it must not read is made unreadable to others (the
    hidden tests, the book's chapters with every solution, the cache with
    the judges, the submissions, the results with the secret). Its code can
    name no file (tools/grading/compile_wall.py, and the worker's system call
    filter); this is the wall behind those."""
    if sandbox.isolation() != 'unprivileged user':
        return
    if out:
        os.makedirs(out, exist_ok=True)
    sandbox.protect([os.path.join(args.root, 'tests', 'hidden'),
                     os.path.join(args.root, 'chapters'), args.cache, submissions, out])


def main(argv=None):
    parser = FlagsFileParser(description=__doc__.split('\n')[0],
                             formatter_class=argparse.RawDescriptionHelpFormatter,
                             fromfile_prefix_chars='@')
    parser.add_argument('submission', nargs='?')
    parser.add_argument('--batch', metavar='DIR', help='grade every subdirectory or archive')
    parser.add_argument('--out', help='output directory (default build/grade/NAME)')
    parser.add_argument('--root', default=ROOT, help='the book (default: this repository)')
    parser.add_argument('--cache', help='build cache (default ROOT/build/grade/cache)')
    parser.add_argument('--time-limit', type=float, default=10,
                        help='seconds the student\'s code may take to answer one call')
    parser.add_argument('--cpu-limit', type=int, default=300,
                        help='CPU seconds of one worker process')
    parser.add_argument('--exercise-time-limit', type=int, default=900,
                        help='seconds for all the tests of one exercise')
    parser.add_argument('--seed', type=int,
                        help='the secret that draws the random cases (default: new '
                        'each time; give the one a grading used to repeat it)')
    parser.add_argument('--allow-no-sandbox', action='store_true',
                        help='grade even where neither bubblewrap nor an unprivileged '
                        'user can isolate the student\'s code')
    parser.add_argument('--memory-limit', type=int, default=1024,
                        help='MB of address space per test (0: none)')
    parser.add_argument('--judge-memory-limit', type=int, default=4096,
                        help='MB of address space of the judge, which keeps the workers\' '
                        'answers and the failures found in them (0: none)')
    parser.add_argument('--compile-time-limit', type=int, default=900,
                        help='seconds to build the code of one exercise')
    parser.add_argument('--submission-time-limit', type=int, default=3600,
                        help='batch: seconds for one submission')
    parser.add_argument('--cxxflags', default=DEFAULT_CXXFLAGS)
    parser.add_argument('--build-jobs', type=int, default=2)
    parser.add_argument('--workers', type=int, default=2, help='batch: parallel (at most 2)')
    parser.add_argument('--chapters', action='append', metavar='"NN ..."',
                        help='grade the exercises of these chapters only (numbers, '
                        'separated by spaces or commas; default: the chapters of the '
                        "kit's exercises.json, else every chapter with exercises)")
    parser.add_argument('--plan', metavar='FILE',
                        help='a course plan (docs/course.md): grade the exercises of '
                        '--assignment with the plan\'s points')
    parser.add_argument('--assignment', metavar='NAME', help='an assignment of --plan')
    parser.add_argument('--roster', metavar='FILE',
                        help='batch: a CSV of submission,student,login rows (several '
                        'rows for a group) saying whose each submission is (default: '
                        'its name)')
    parser.add_argument('--allow-changes-outside-exercises', action='store_true')
    parser.add_argument('--quiet', action='store_true')
    args = parser.parse_args(argv)
    args.root = os.path.abspath(args.root)
    args.cache = os.path.abspath(args.cache or os.path.join(args.root, 'build', 'grade',
                                                            'cache'))
    if args.seed is None:
        args.secret = secrets.randbits(62)
    else:
        args.secret = args.seed
    if sandbox.isolation() == 'none' and not args.allow_no_sandbox:
        parser.error('the student\'s code cannot be isolated here (no working bubblewrap, '
                     'and not root): install bubblewrap, run as root, or give '
                     '--allow-no-sandbox for a grade that the code could forge')
    if args.roster and not args.batch:
        parser.error('--roster goes with --batch')
    if args.batch:
        if not os.path.isdir(args.batch):
            parser.error('--batch %s is not a directory' % args.batch)
        protect_from_the_sandbox(args, args.batch, args.out and os.path.abspath(args.out))
        return grade_batch(args)
    if not args.submission:
        parser.error('give a SUBMISSION (a directory, .tar.gz or .zip) or --batch DIR')
    if not os.path.exists(args.submission):
        parser.error('%s does not exist' % args.submission)
    out = os.path.abspath(args.out or default_out(parser, args.root, args.submission))
    protect_from_the_sandbox(args, args.submission, out)
    sandbox.adopt_orphans()
    report = grade(args, os.path.abspath(args.submission), out)
    if not args.quiet:
        with open(os.path.join(out, 'results.txt'), encoding='utf-8') as f:
            sys.stdout.write(f.read())
        print('results: %s' % os.path.join(out, 'results.json'))
    return 1 if report.failed else 0


if __name__ == '__main__':
    sys.exit(main())
