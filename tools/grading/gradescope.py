#!/usr/bin/env python3
"""Writes a Gradescope autograder: a zip that Gradescope unpacks into
/autograder/source (docs/grading.md, "Gradescope").

    tools/grading/gradescope.py --out build/gradescope/autograder.zip
                        [--chapters "05"] [--plan PLAN --assignment NAME]
                        [-- GRADE.PY FLAGS...]

The zip holds, at its top, what grading needs and nothing else:

- setup.sh and run_autograder (from gradescope/), which Gradescope runs;
- grade_flags: the arguments run_autograder and setup.sh pass to
  tools/grading/grade.py, one per line (what is graded: --chapters, or --plan and
  --assignment; and any other flag given here). Edit it in the zip, or set
  GRADE_FLAGS in Gradescope's environment, to change them without touching
  a script;
- course.toml, the plan, when one is given;
- the chapters, their public and hidden tests, tests/calls/, and the tools grading runs (tools/grading/grade.py and what it
  imports, tools/noweb/tangle.py and its filters, tools/deps.sh).
"""
import argparse
import os
import re
import stat
import sys
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(os.path.dirname(HERE)))  # the repository: import tools.*
from tools.exercises import course  # noqa: E402

TOOLS = ['__init__.py', 'deps.sh', 'grading/__init__.py', 'grading/grade.py', 'grading/build.py',
         'grading/sandbox.py', 'grading/compile_wall.py', 'exercises/__init__.py',
         'exercises/markup.py', 'exercises/regions.py', 'exercises/attributes.py',
         'exercises/book.py', 'exercises/suites.py', 'exercises/student.py',
         'exercises/course.py', 'noweb/__init__.py', 'noweb/tangle.py', 'noweb/chunks.py',
         'noweb/markup_filter.py', 'noweb/fragment_comments.py']
SCRIPTS = ['setup.sh', 'run_autograder']
PLAN_NAME = 'course.toml'


def fail(message):
    sys.exit('gradescope: ' + message)


def graded(root, chapters, plan, assignment):
    """(chapter numbers graded, flags naming what is graded)."""
    book = course.book_in(root)
    with_exercises = [c.number for c in book.chapters if c.exercises]
    if plan:
        if chapters:
            fail('give CHAPTERS or PLAN, not both')
        if not assignment:
            fail('PLAN needs ASSIGNMENT (one autograder grades one assignment)')
        try:
            chosen = course.load(plan, {e.id: e.points for e in book.exercises}) \
                .assignment(assignment)
        except course.PlanError as e:
            fail(str(e))
        numbers = sorted({e.chapter for e in book.exercises if e.id in chosen.exercises})
        return numbers, ['--plan', PLAN_NAME, '--assignment', assignment]
    if assignment:
        fail('ASSIGNMENT needs PLAN')
    if not chapters:
        return with_exercises, []
    numbers = []
    for word in re.split(r'[\s,]+', ' '.join(chapters).strip()):
        m = re.match(r'^(?:.*/)?(\d{1,2})(?:-[^/]*\.md)?$', word)
        number = '%02d' % int(m.group(1)) if m else None
        if number not in with_exercises:
            fail('%r is not a chapter with exercises (%s)' % (word, ' '.join(with_exercises)))
        numbers.append(number)
    numbers = sorted(set(numbers))
    return numbers, ['--chapters', ' '.join(numbers)]


def add(z, source, name, executable=False):
    info = zipfile.ZipInfo(name, date_time=(2020, 1, 1, 0, 0, 0))
    mode = 0o755 if executable or os.access(source, os.X_OK) else 0o644
    info.external_attr = (stat.S_IFREG | mode) << 16
    info.compress_type = zipfile.ZIP_DEFLATED
    with open(source, 'rb') as f:
        z.writestr(info, f.read())


def add_tree(z, root, rel, skip=()):
    top = os.path.join(root, rel)
    for d, dirs, files in os.walk(top):
        dirs[:] = sorted(x for x in dirs if x != '__pycache__' and
                         not (d == top and x in skip))
        for name in sorted(files):
            path = os.path.join(d, name)
            add(z, path, os.path.relpath(path, root))


def write(out, root, flags, plan):
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    tmp = out + '.tmp'
    with zipfile.ZipFile(tmp, 'w') as z:
        for name in SCRIPTS:
            add(z, os.path.join(root, 'gradescope', name), name, executable=True)
        for name in TOOLS:
            add(z, os.path.join(root, 'tools', name), 'tools/' + name)
        # Every chapter and its tests: grading checks the whole book's
        # exercise markup, and a plan names exercises of any chapter.
        for name in sorted(os.listdir(os.path.join(root, 'chapters'))):
            if re.match(r'^\d\d-.*\.md$', name):
                add(z, os.path.join(root, 'chapters', name), 'chapters/' + name)
        add_tree(z, root, 'tests', skip=('tools',))
        if plan:
            add(z, plan, PLAN_NAME)
        info = zipfile.ZipInfo('grade_flags', date_time=(2020, 1, 1, 0, 0, 0))
        info.external_attr = (stat.S_IFREG | 0o644) << 16
        z.writestr(info, '# The arguments that run_autograder and setup.sh pass to '
                   'tools/grading/grade.py,\n# one per line (docs/grading.md). GRADE_FLAGS in the '
                   'environment adds more.\n' + ''.join(f + '\n' for f in flags))
    os.replace(tmp, out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--out', required=True)
    parser.add_argument('--root', default=ROOT)
    parser.add_argument('--chapters', action='append', default=[])
    parser.add_argument('--plan')
    parser.add_argument('--assignment')
    parser.add_argument('grade_flags', nargs='*', help='more flags for tools/grading/grade.py')
    args = parser.parse_args(argv)
    root = os.path.abspath(args.root)
    plan = os.path.abspath(args.plan) if args.plan else None
    numbers, flags = graded(root, [c for c in args.chapters if c.strip()], plan,
                            args.assignment)
    if not numbers:
        fail('nothing to grade: no chapter has exercises')
    write(args.out, root, flags + args.grade_flags, plan)
    shown = os.path.relpath(args.out)
    print('gradescope: %s grades chapter%s %s%s; upload it as the autograder' % (
        args.out if shown.startswith('..') else shown, 's' if len(numbers) > 1 else '', ' '.join(numbers),
        ' (assignment %s of %s)' % (args.assignment, args.plan) if plan else ''))


if __name__ == '__main__':
    main()
