#!/usr/bin/env python3
"""A course plan: the assignments of a course, each with its exercises, their
points and its place in the release order (docs/course.md).

    tools/exercises/course.py check PLAN.toml             check a plan against the book
    tools/exercises/course.py show PLAN.toml [ASSIGNMENT] the assignments, or one

The plan is TOML (Python's tomllib reads it):

    title = "Rendering, fall 2027"

    [[assignment]]
    name = "a1"                       # letters, digits, - and _
    title = "Geometry"                # optional
    release = 2027-09-06              # optional, a TOML date or date-time
    due = 2027-09-20T23:59:00         # optional, not before release
    exercises = ["ex-2.13", "ex-2.14"]
    points = { "ex-2.14" = 6 }        # optional: overrides the chapter's

Assignments are released in the order they are written (release dates, where
given, must not go back). An exercise belongs to at most one assignment; an
exercise in no assignment is not graded in this course. A mistake stops
everything with the plan's file, line and key.

Used by tools/grading/grade.py (--plan, --assignment), tools/exercises/kits.py (the
kits of one assignment) and tools/gradescope.py.
"""
import argparse
import datetime
import os
import re
import sys
try:
    import tomllib                    # Python 3.11 (Debian 12)
except ImportError:                   # older Pythons, e.g. Ubuntu 22.04's 3.10
    try:
        import tomli as tomllib       # the same parser (python3-tomli)
    except ImportError:
        tomllib = None


# The repository, for `import tools.*` when this file is run as a script.
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

NAME = re.compile(r'^[A-Za-z0-9][A-Za-z0-9_-]*$')
TOP_KEYS = {'title', 'assignment'}
ASSIGNMENT_KEYS = {'name', 'title', 'release', 'due', 'exercises', 'points'}


class PlanError(Exception):
    pass


class Assignment:
    def __init__(self, index, name, title, release, due, exercises, points):
        self.index, self.name, self.title = index, name, title
        self.release, self.due = release, due
        self.exercises = exercises   # exercise ids, in the plan's order
        self.points = points         # exercise id -> points (the plan's or the chapter's)

    def as_dict(self):
        return {'name': self.name, 'title': self.title,
                'release': self.release.isoformat() if self.release else None,
                'due': self.due.isoformat() if self.due else None,
                'exercises': self.exercises, 'points': self.points,
                'total': sum(self.points.values())}


class Plan:
    def __init__(self, path, title, assignments):
        self.path, self.title, self.assignments = path, title, assignments

    def assignment(self, name):
        for a in self.assignments:
            if a.name == name:
                return a
        raise PlanError('%s: no assignment named %r (assignments: %s)' % (
            self.path, name, ', '.join(a.name for a in self.assignments) or 'none'))

    def graded(self):
        """Every exercise the course grades: {id: assignment}."""
        return {e: a for a in self.assignments for e in a.exercises}

    def unreleased(self, name):
        """The exercises of the assignments released after `name`."""
        current = self.assignment(name)
        return [e for a in self.assignments[current.index + 1:] for e in a.exercises]


def _lines(text):
    return text.split('\n')


def _where(path, text, index, key=None):
    """'path:line' of assignment `index` (0-based), or of its key `key`."""
    lines = _lines(text)
    headers = [n for n, line in enumerate(lines, 1)
               if re.match(r'^\s*\[\[\s*assignment\s*\]\]', line)]
    if index is None or index >= len(headers):
        line = None
        if key is not None:
            line = next((n for n, t in enumerate(lines, 1)
                         if re.match(r'^\s*%s\s*=' % re.escape(key), t)), None)
        return '%s:%d' % (path, line) if line else path
    start = headers[index]
    end = headers[index + 1] if index + 1 < len(headers) else len(lines) + 1
    if key is not None:
        for n in range(start + 1, end):
            if re.match(r'^\s*"?%s"?\s*=' % re.escape(key), lines[n - 1]):
                return '%s:%d' % (path, n)
    return '%s:%d' % (path, start)


def _moment(value):
    """A TOML date or date-time as a datetime (dates at midnight), or None."""
    if isinstance(value, datetime.datetime):
        return value.replace(tzinfo=None)
    if isinstance(value, datetime.date):
        return datetime.datetime(value.year, value.month, value.day)
    return None


def load(path, book_exercises):
    """Reads and checks a plan. book_exercises: {exercise id: points in the
    chapter}, in the book's order. Raises PlanError naming file, line and key."""
    shown = os.path.relpath(path) if not os.path.relpath(path).startswith('..') else path
    try:
        with open(path, 'rb') as f:
            raw = f.read()
    except OSError as e:
        raise PlanError('%s: cannot read the course plan (%s)' % (shown, e.strerror))
    if tomllib is None:
        raise PlanError('%s: reading a course plan needs Python 3.11 (tomllib) or the '
                        'python3-tomli package' % shown)
    try:
        text = raw.decode('utf-8')
        data = tomllib.loads(text)
    except UnicodeDecodeError:
        raise PlanError('%s: not UTF-8 text' % shown)
    except tomllib.TOMLDecodeError as e:
        m = re.search(r'\(at line (\d+), column (\d+)\)', str(e))
        if m:
            where = '%s:%s:%s' % (shown, m.group(1), m.group(2))
        else:   # "(at end of document)"
            where = '%s:%d' % (shown, len(text.rstrip('\n').split('\n')))
        raise PlanError('%s: not valid TOML: %s' % (where, re.sub(r'\s*\(at .*\)$', '',
                                                                  str(e))))
    errors = []

    def error(index, key, message):
        errors.append('%s: %s' % (_where(shown, text, index, key), message))

    for key in sorted(set(data) - TOP_KEYS):
        error(None, key, 'unknown key %r (a plan has: title, [[assignment]])' % key)
    title = data.get('title')
    if title is not None and not isinstance(title, str):
        error(None, 'title', 'title must be a string')
    entries = data.get('assignment')
    if not isinstance(entries, list) or not entries:
        raise PlanError('%s: the plan has no [[assignment]] table' % shown)
    assignments, owner, names = [], {}, set()
    last_release = None
    for index, entry in enumerate(entries):
        label = 'assignment %d' % (index + 1)
        for key in sorted(set(entry) - ASSIGNMENT_KEYS):
            error(index, key, '%s: unknown key %r (an assignment has: %s)'
                  % (label, key, ', '.join(sorted(ASSIGNMENT_KEYS))))
        name = entry.get('name')
        if not isinstance(name, str) or not NAME.match(name):
            error(index, 'name' if 'name' in entry else None,
                  '%s: name must be letters, digits, - and _ (got %r)' % (label, name))
            name = None
        elif name in names:
            error(index, 'name', '%s: the name %r is used twice' % (label, name))
        else:
            names.add(name)
            label = 'assignment %r' % name
        a_title = entry.get('title')
        if a_title is not None and not isinstance(a_title, str):
            error(index, 'title', '%s: title must be a string' % label)
        moments = {}
        for key in ('release', 'due'):
            if key in entry:
                moments[key] = _moment(entry[key])
                if moments[key] is None:
                    error(index, key, '%s: %s must be a TOML date (2027-09-06) or date-time '
                          '(2027-09-20T23:59:00), not %r' % (label, key, entry[key]))
        release, due = moments.get('release'), moments.get('due')
        if release and due and due < release:
            error(index, 'due', '%s: due %s is before release %s' % (label, due, release))
        if release:
            if last_release and release < last_release:
                error(index, 'release', '%s: released %s, before the assignment above it '
                      '(%s): assignments are released in the order they are written'
                      % (label, release, last_release))
            last_release = release
        ids = entry.get('exercises')
        if not isinstance(ids, list) or not ids or \
                not all(isinstance(e, str) for e in ids):
            error(index, 'exercises' if 'exercises' in entry else None,
                  '%s: exercises must be a non-empty list of exercise ids ("ex-5.9")' % label)
            ids = []
        chosen = []
        for ident in ids:
            if ident not in book_exercises:
                error(index, 'exercises', '%s: %s is not an exercise of the book (exercises: '
                      '%s)' % (label, ident, ' '.join(book_exercises)))
            elif ident in owner:
                error(index, 'exercises', '%s: %s is already in %s' % (label, ident,
                                                                       owner[ident]))
            elif ident in chosen:
                error(index, 'exercises', '%s: %s is listed twice' % (label, ident))
            else:
                chosen.append(ident)
        for ident in chosen:
            owner[ident] = label
        points = {e: book_exercises[e] for e in chosen}
        given = entry.get('points', {})
        if not isinstance(given, dict):
            error(index, 'points', '%s: points must be a table { "ex-5.9" = 4 }' % label)
            given = {}
        for ident, value in given.items():
            if ident not in ids:
                error(index, 'points', '%s: points for %s, which is not among its exercises'
                      % (label, ident))
            elif isinstance(value, bool) or not isinstance(value, (int, float)) or \
                    value <= 0:
                error(index, 'points', '%s: the points of %s must be a positive number, not %r'
                      % (label, ident, value))
            elif ident in points:
                points[ident] = value
        assignments.append(Assignment(index, name, a_title, release, due, chosen, points))
    if errors:
        raise PlanError('\n'.join(errors))
    return Plan(shown, title, assignments)


def book_in(root):
    """The exercises of the book in root (markup.Book, tests not read)."""
    from tools.exercises import markup
    chapters = sorted(os.path.join('chapters', f) for f in os.listdir(
        os.path.join(root, 'chapters')) if re.match(r'^\d\d-.*\.md$', f))
    cwd = os.getcwd()
    os.chdir(root)
    try:
        return markup.load(chapters, root=root, tests=False)
    finally:
        os.chdir(cwd)


def load_for_book(path, root):
    """A plan checked against the book in root."""
    return load(path, {e.id: e.points for e in book_in(root).exercises})


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('command', choices=('check', 'show'))
    parser.add_argument('plan')
    parser.add_argument('assignment', nargs='?')
    parser.add_argument('--root', default=os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
    args = parser.parse_args(argv)
    try:
        plan = load_for_book(os.path.abspath(args.plan), args.root)
        chosen = [plan.assignment(args.assignment)] if args.assignment else plan.assignments
    except PlanError as e:
        sys.exit(str(e))
    if args.command == 'check':
        print('%s: %d assignments, %d exercises graded' % (
            plan.path, len(plan.assignments), len(plan.graded())))
        return
    for a in chosen:
        print('%s%s: %g points, released %s, due %s' % (
            a.name, ' (%s)' % a.title if a.title else '', sum(a.points.values()),
            a.release or '-', a.due or '-'))
        for e in a.exercises:
            print('    %-8s %g' % (e, a.points[e]))


if __name__ == '__main__':
    main()
