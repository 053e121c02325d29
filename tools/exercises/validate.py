"""The validation of a pair of kits (tools/exercises/kits.py validate).

The solution kit, built as of every chapter with that chapter's public and
hidden tests and as of the last chapter with all of them, must pass every
test. Graded by tools/grading/grade.py in the solution kit, each chosen
chapter must score every point, and lose exactly one exercise's points with
that exercise alone stubbed. The student kit must compile as of every
chapter; and for each chosen chapter N, the code as of N built as grading
builds it (the student's chapter N, the reference text of the chapters
before it) must fail every test of chapter N's exercises, with at least one
failure naming the exercise (as the stubs do), and pass chapter N's other
tests. The kits' test binaries are built by tools/make/hidden.mk and run by
tools/testing/gtest.py.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
from tools.exercises import markup  # noqa: E402
from tools.exercises.kit_common import (EDITIONS, clean_env, make, read_bytes,  # noqa: E402
                                        run_gtest, shown, stop_on)
from tools.testing import gtest  # noqa: E402

# What `validate` checks: each edition's tests, then grading in the solution kit.
VALIDATIONS = EDITIONS + ('grading',)
TEST_TIME_LIMIT = 120   # seconds for one test, when a binary must be run test by test


class Run:
    """One test's result in one binary: passed or not, and its failure text."""
    def __init__(self, label, suite, name, passed, output):
        self.label, self.suite, self.name = label, suite, name
        self.passed, self.output = passed, output

    @property
    def full_name(self):
        return '%s.%s' % (self.suite, self.name)


def run_binary(label, binary):
    """Runs a test binary: a Run for each of its tests that ran."""
    output, code, suites = run_gtest(binary)
    if suites is None:
        # The binary died (a crash, an abort, a hang): run its tests one by one
        # so that each gets its own verdict.
        runs = []
        for suite, name in gtest.list_tests(binary, env=clean_env()):
            out, _, one = run_gtest(binary, '%s.%s' % (suite, name), TEST_TIME_LIMIT)
            passed = bool(one) and all(not t.get('failures') for _, t in gtest.tests(one))
            runs.append(Run(label, suite, name, passed,
                            out if one is None else gtest.failure_text(one)))
        return runs
    return [Run(label, suite, test['name'], not test.get('failures'), gtest.failure_text(test))
            for suite, test in gtest.tests(suites) if gtest.ran(test)]


def build_and_run(kit, chapters, number, only, hidden, build_dir, jobs, run=True):
    """In directory kit, builds the code as of chapter `number` from the given
    chapter files, with the public tests of chapter `only` (of every chapter
    up to `number` if None) and the hidden tests from directory `hidden`, and
    runs them unless run is false. Returns (runs, errors)."""
    common = ['-f', 'tools/make/hidden.mk', 'CHAPTERS=' + ' '.join(chapters),
              'BUILD=' + build_dir, 'HIDDEN=' + hidden, 'ASOF=' + number] + \
             (['ONLY=' + only] if only else [])
    proc = make(kit, common + ['tangle'])
    if proc.returncode != 0:
        return [], ['as of chapter %s: the tangle failed:\n%s' % (number, proc.stderr)]
    proc = make(kit, common + ['-j%d' % jobs, 'lib', 'tests', 'hidden-tests'])
    if proc.returncode != 0:
        output = proc.stdout + proc.stderr
        first = [l for l in output.splitlines() if ': error' in l or 'Error' in l][:15]
        return [], ['as of chapter %s: the code or its tests do not compile (paths are '
                    'relative to %s):\n  %s' % (number, shown(kit), '\n  '.join(first))]
    runs = []
    if run:
        listing = make(kit, common + ['-s', 'list-tests', 'list-hidden-tests'])
        for item in listing.stdout.split():
            label, binary = item.split('=', 1)
            runs.extend(run_binary(label, os.path.join(kit, binary)))
    return runs, []


def judge(edition, runs, chosen, errors):
    """Checks each run against what the edition expects; returns the number of
    runs of chosen exercises' tests."""
    exercise_runs = 0
    for run in runs:
        exercise_id = markup.Book.suite_exercise(run.suite)
        if edition == 'solution' or exercise_id not in chosen:
            if not run.passed:
                errors.append('%s: %s %s fails%s:\n    %s' % (
                    edition, run.label, run.full_name, '' if edition == 'solution' else
                    ' (it belongs to no exercise of this set, so it must pass)',
                    run.output.strip().replace('\n', '\n    ')[:1500]))
        else:
            exercise_runs += 1
            if run.passed:
                errors.append('student: %s %s passes with the stub of %s: a stub must '
                              'fail every test of its exercise (does the test check '
                              'anything the stub does not?)' % (run.label, run.full_name,
                                                                exercise_id))
    return exercise_runs


def check_expected(edition, runs, exercise_list, errors):
    """Every test of every exercise ran; in the student edition, some failure
    of each exercise names it (the stub's message)."""
    seen = {}
    for run in runs:
        seen.setdefault(run.full_name, []).append(run)
    for e in exercise_list:
        expected = e['public_tests'] + e['hidden_tests']
        missing = sorted(set(expected) - set(seen))
        if missing:
            errors.append('%s: tests of %s never ran: %s' % (edition, e['id'],
                                                              ', '.join(missing)))
        failures = [r for name in expected for r in seen.get(name, []) if not r.passed]
        if edition == 'student' and failures and \
                not any(e['id'] in r.output for r in failures):
            errors.append('student: no failing test of %s names the exercise in its '
                          'output: a stub block should hold "// NOT IMPLEMENTED", which '
                          'becomes the throw that does' % e['id'])


def validate_solution(out, manifest, jobs):
    """Every public and hidden test passes: each chapter's as of that chapter,
    and every chapter's as of the last one."""
    kit = os.path.join(out, 'solution')
    chapters = manifest['chapters']
    runs, errors = [], []
    for chapter in chapters:
        number = markup.chapter_number(chapter)
        last = chapter == chapters[-1]
        r, e = build_and_run(kit, chapters, number, None if last else number,
                             'tests/hidden', os.path.join(out, 'validate', 'solution'), jobs)
        runs += r
        errors += ['solution: ' + x for x in e]
    judge('solution', runs, {}, errors)
    if not errors:
        check_expected('solution', runs, manifest['exercises'], errors)
    return runs, errors, ''


def validate_student(out, manifest, jobs):
    """The student kit compiles as of every chapter. For each chosen chapter N,
    the code as of N built as grading builds it (the student's chapter N, the
    reference text of the chapters before it) fails every test of chapter N's
    exercises, public and hidden, and passes chapter N's other tests."""
    kit = os.path.join(out, 'student')
    solution = os.path.join(out, 'solution')
    chapters = manifest['chapters']
    chosen = {e['id']: e for e in manifest['exercises']}
    # A plan's later assignments: stubs too, whose tests must fail as well.
    stubbed = dict(chosen, **{e: None for e in manifest.get('unreleased', [])})
    runs, errors = [], []
    hidden = os.path.join(solution, 'tests', 'hidden')
    # While the student's chapters are the solution's, so is the code: the
    # solution's validation covers it. At the first chosen chapter N, the kit
    # is the grading build of chapter N; after it, the kit is only compiled and
    # chapter N is tested in a build of its own.
    same_so_far = True
    for chapter in chapters:
        number = markup.chapter_number(chapter)
        same = read_bytes(os.path.join(kit, chapter)) == read_bytes(
            os.path.join(solution, chapter))
        graded = any(e['chapter'] == number for e in chosen.values())
        if same_so_far and same:
            continue
        r, e = build_and_run(kit, chapters, number, number, hidden,
                             os.path.join(out, 'validate', 'student'), jobs,
                             run=same_so_far and graded)
        runs += r
        errors += ['student: ' + x for x in e]
        if graded and not same_so_far:
            own = os.path.relpath(os.path.join(kit, chapter), solution)
            mixed = [c for c in chapters if markup.chapter_number(c) < number] + [own]
            r, e = build_and_run(solution, mixed, number, number, 'tests/hidden',
                                 os.path.join(out, 'validate', 'student-' + number), jobs)
            runs += r
            errors += ['student: ' + x for x in e]
        same_so_far = same_so_far and same
    exercise_runs = judge('student', runs, stubbed, errors)
    if not errors:
        check_expected('student', runs, manifest['exercises'], errors)
    return runs, errors, ', %d of them exercise tests that must fail' % exercise_runs


def validate_grading(out, manifest, jobs):
    """Grading, as tools/grading/grade.py does it, in the solution kit: for each chosen
    chapter, the book's chapter scores every point; and for each exercise, the
    chapter with that exercise alone stubbed (every other one solved) loses
    that exercise's points, every test of it failing, and keeps all others."""
    kit = os.path.join(out, 'solution')
    book = markup.load([os.path.join(kit, c) for c in manifest['chapters']], root=kit,
                          tests=False)
    chosen = {e['id']: e for e in manifest['exercises']}
    work = os.path.join(out, 'validate', 'grading')
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    # One secret for all: verdicts of unchanged exercises are reused.
    seed = str(int.from_bytes(os.urandom(7), 'little'))
    runs, errors = [], []
    for chapter in book.chapters:
        mine = [e for e in chapter.exercises if e.id in chosen]
        if not mine:
            continue
        cases = [('solution', None)] + [('%s stubbed' % e.id, e) for e in mine]
        for label, stubbed in cases:
            name = re.sub(r'[^\w.-]', '_', '%s-%s' % (chapter.number, label))
            sub = os.path.join(work, 'submissions', name, 'chapters')
            os.makedirs(sub)
            lines = chapter.lines if stubbed is None else \
                markup.student_edition(chapter, only=stubbed)
            with open(os.path.join(sub, os.path.basename(chapter.path)), 'w',
                      encoding='utf-8') as f:
                f.write('\n'.join(lines))
            target = os.path.join(work, 'results', name)
            proc = subprocess.run([sys.executable, os.path.join(kit, 'tools', 'grading', 'grade.py'),
                                   '--root', kit, '--chapters', chapter.number,
                                   '--seed', seed, '--build-jobs', str(jobs),
                                   '--cache', os.path.join(out, 'validate', 'grade-cache'),
                                   '--out', target, '--quiet', os.path.dirname(sub)],
                                  capture_output=True, text=True, env=clean_env())
            try:
                with open(os.path.join(target, 'results.json'), encoding='utf-8') as f:
                    data = json.load(f)
            except (OSError, ValueError):
                errors.append('grading %s of chapter %s: no results (%s)' % (
                    label, chapter.number, (proc.stdout + proc.stderr)[-1500:]))
                continue
            for test in data['tests']:
                exercise_id, full = test['name'].split(' ', 1)
                status = test['tags'][0]
                lost = stubbed is not None and exercise_id == stubbed.id
                runs.append(Run('grading %s' % label, *full.split('.', 1),
                                passed=status == 'PASS', output=test['output']))
                if lost and status == 'PASS':
                    errors.append('grading with %s: %s passes with the stub: it does not '
                                  'reach the exercise\'s code through its exercise calls'
                                  % (label, full))
                elif not lost and status != 'PASS':
                    errors.append('grading %s of chapter %s: %s %s scores %s:\n    %s' % (
                        label, chapter.number, exercise_id, full, status,
                        test['output'].replace('\n', '\n    ')[:1500]))
            expected = sum(e.points for e in mine) - (stubbed.points if stubbed else 0)
            if abs(data['score'] - expected) > 1e-6:
                errors.append('grading %s of chapter %s scores %g, not %g' % (
                    label, chapter.number, data['score'], expected))
            if stubbed is not None and not any(
                    stubbed.id in t['output'] for t in data['tests']
                    if t['name'].startswith(stubbed.id + ' ')):
                errors.append('grading with %s: no failure names the exercise (the stub\'s '
                              'message)' % label)
    return runs, errors, ' (seed %s)' % seed


def command(args):
    out = os.path.abspath(args.out)
    with open(os.path.join(out, 'solution', 'exercises.json'), encoding='utf-8') as f:
        manifest = json.load(f)
    errors = []
    for edition in args.edition or VALIDATIONS:
        if edition != 'solution' and errors:
            print('validate: %s not checked: fix the solution edition first' % edition)
            break
        started = time.time()
        runs, e, note = {'solution': validate_solution, 'student': validate_student,
                         'grading': validate_grading}[edition](out, manifest, args.jobs)
        passed = sum(1 for r in runs if r.passed)
        print('validate: %s: %d test runs, %d passed, %d failed%s (%.0f s)' % (
            edition + (' edition' if edition in EDITIONS else ''), len(runs), passed,
            len(runs) - passed, note, time.time() - started))
        errors += e
    stop_on(errors, 'validation failed (%d problems)')
    print('validate: the solutions pass every test; the stubs fail every test of their '
          'exercise (%d exercises) and only those, in the kits and in grading, one '
          'exercise stubbed at a time' % len(manifest['exercises']))
