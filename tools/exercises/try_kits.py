"""Trying the kits as their readers use them (tools/exercises/kits.py try).

The student kit's own `make test` (with MAKE_ARGs, e.g. UPTO=last) may fail a
test only because of the chosen exercises' stubs (their tests, or a later
chapter's test whose failure names one), and skip a test only at the stub of
a later assignment's exercise; each chosen exercise fails some test. The
solution kit's chapters and tests must be the source's, which the source's
own `make test` runs.
"""
import glob
import json
import os
import re
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
from tools.exercises import markup  # noqa: E402
from tools.exercises.kit_common import ROOT, make, read_bytes, run_gtest, stop_on  # noqa: E402
from tools.testing import gtest  # noqa: E402


def result_lines(output, kind):
    """runtests.py's 'FAILED: LABEL NAME' or 'SKIPPED: LABEL NAME: REASON'
    lines, as (label, name, reason)."""
    found = []
    for line in output.splitlines():
        if line.startswith(kind + ': '):
            label, _, rest = line[len(kind) + 2:].partition(' ')
            name, _, reason = rest.partition(': ')
            found.append((label, name, reason))
    return found


def kit_binary(kit, label):
    """The test binary that `make test` labelled asofNN/chMM (tools/make/asof.mk)."""
    asof = label.split('/')[0]
    chapters = sorted(glob.glob(os.path.join(kit, 'chapters', '[0-9][0-9]-*.md')))
    listing = make(kit, ['-s', '-f', 'tools/make/asof.mk', 'ASOF=' + asof[len('asof'):],
                         'CHAPTERS=' + ' '.join(os.path.relpath(c, kit) for c in chapters),
                         'BUILD=build', 'list-tests']).stdout
    for item in listing.split():
        if item.startswith(label + '='):
            return os.path.join(kit, item.split('=', 1)[1])
    return None


def same_as_source(out, src, manifest):
    """Problems if the solution kit's chapters or tests differ from the
    source's: then the source's own `make test` and `make validate-exercises`
    do not speak for them."""
    kit = os.path.join(out, 'solution')
    problems = []
    for top in manifest['chapters'] + ['tests']:
        for path in ([os.path.join(kit, top)] if top.endswith('.md') else
                     [os.path.join(d, f) for d, _, fs in os.walk(os.path.join(kit, top))
                      for f in fs]):
            rel = os.path.relpath(path, kit)
            origin = os.path.join(ROOT if rel.startswith(('tests/tools/', 'tests/calls/'))
                                  else src, rel)
            if not os.path.isfile(origin) or read_bytes(origin) != read_bytes(path):
                problems.append('solution: %s is not the source\'s %s' % (rel, origin))
    return problems


def try_student(out, manifest, make_args):
    """Runs `make test` with make_args in the student kit, as its reader
    would, and returns (summary, problems). A test may fail only because of
    the assignment's own stubs: a test of a chosen exercise, or a test whose
    failure names a chosen exercise's stub (a later chapter's test that uses
    that code); it may be skipped only by the stub of a later assignment's
    exercise (tests/calls/rpc.h, IsLater); and each chosen exercise whose chapter's
    tests ran fails some test."""
    kit = os.path.join(out, 'student')
    proc = make(kit, ['test'] + make_args)
    output = proc.stdout + proc.stderr
    summary = ([l for l in proc.stdout.splitlines() if l.startswith('tests: ')] or
               ['no summary'])[-1]
    failed, skipped = result_lines(proc.stdout, 'FAILED'), result_lines(proc.stdout, 'SKIPPED')
    problems = []
    if not summary.startswith('tests: ') or summary.startswith('tests: 0 passed'):
        problems.append('student: make test %s ran no tests:\n%s' % (
            ' '.join(make_args), output[-3000:]))
    chosen = {e['id'] for e in manifest['exercises']}
    later = set(manifest.get('unreleased', []))
    for label, name, reason in skipped:
        match = re.match(r'Exercise (\S+) comes with a later assignment: ', reason)
        if not match or match.group(1) not in later:
            problems.append('student: %s %s is skipped (%s): only a later assignment\'s '
                            'stub may skip a test' % (label, name, reason))
    failed_exercises = set()
    for label, name, _ in failed:
        exercise_id = markup.Book.suite_exercise(name.split('.')[0])
        if exercise_id in chosen:
            failed_exercises.add(exercise_id)
            continue
        # Why did it fail? Its binary, run again for this test alone, says.
        binary = kit_binary(kit, label) if re.match(r'^asof\d+/ch\d+$', label) else None
        text, _, suites = run_gtest(binary, name) if binary else (output[-3000:], None, None)
        if suites is not None:
            text = gtest.failure_text(suites)
        names = set(re.findall(r'Exercise (\S+) is not done yet', text))
        if not names or not names <= chosen:
            problems.append('student: %s %s fails, and not only because of this '
                            'assignment\'s stubs:\n    %s' % (
                                label, name, text.strip().replace('\n', '\n    ')[:1500]))
    ran = set(re.findall(r'^asof\d+/ch(\d+) ', proc.stdout, re.M))
    for e in manifest['exercises']:
        if e['chapter'] in ran and e['id'] not in failed_exercises:
            problems.append('student: no test of %s fails: its stub is not reached'
                            % e['id'])
    return summary, problems


def command(args):
    out = os.path.abspath(args.out)
    with open(os.path.join(out, 'solution', 'exercises.json'), encoding='utf-8') as f:
        manifest = json.load(f)
    started = time.time()
    problems = same_as_source(out, os.path.abspath(args.src), manifest)
    summary, p = try_student(out, manifest, args.make_args)
    problems += p
    print('try: student kit: make test %s: %s (%.0f s)' % (
        ' '.join(args.make_args), summary, time.time() - started))
    stop_on(problems, 'the kits do not work as their READMEs say (%d problems)')
    print('try: in the student kit only the assignment\'s stubs fail tests, and only '
          'later assignments\' stubs skip them; the solution kit\'s chapters and tests '
          'are the source\'s, whose tests make test runs')
