"""Batch mode (grade.py --batch DIR): every submission in DIR graded by a
grade.py of its own, into OUT/NAME/; OUT/grades.csv (a row per student and
exercise) and OUT/gradebook.csv (a row per student, a column per exercise
and the total). Who submitted comes from the submission's name or from an
instructor's roster (--roster), never from a file inside the submission."""
import atexit
import concurrent.futures
import csv
import io
import json
import os
import re
import shutil
import sys
import tempfile
import time

from tools.grading import build as grade_build
from tools.grading.files import atomic_write, write_private
from tools.grading.feedback import first_line
from tools.grading.selection import graded_chapters, graded_exercises, load_book
from tools.grading.submission import printable

# The grader that grades each submission, as a process of its own.
GRADE = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'grade.py')


# A batch names each submission's results directory, OUT/NAME, after the
# submission (its folder, or its archive without .zip/.tar.gz/.tgz), and that
# name is the student's identity unless a roster says otherwise. Only names
# that are one plain path component qualify: a name such as ".." or "" would
# make OUT/NAME a directory outside OUT's results (OUT's parent, or OUT
# itself), which the batch empties before grading.
SAFE_NAME = re.compile(r'[A-Za-z0-9][A-Za-z0-9._-]*')
MAX_NAME = 100
# Files and directories of OUT that are not a student's results (the
# temporary files that atomic_write() renames over them start with a dot,
# which no safe name does).
RESERVED_NAMES = ('grades.csv', 'gradebook.csv', 'cache')
ARCHIVE_SUFFIX = re.compile(r'\.(tar\.gz|tgz|zip)$')


def name_problem(name):
    """Why a submission's name cannot name its results (None if it can)."""
    if not SAFE_NAME.fullmatch(name):      # (match's $ also takes a final newline)
        return ('a name must start with a letter or digit and hold only letters, '
                'digits, ".", "_" and "-" (ASCII)')
    if '..' in name:
        return 'a name must not contain ".."'
    if name.lower() in RESERVED_NAMES:
        return '%s is the name of a file of the batch\'s own' % name
    if len(name) > MAX_NAME:
        return 'a name must be at most %d characters long' % MAX_NAME
    return None


def submissions_in(directory):
    """[(name, path, problem)] for every entry of directory, problem saying
    why it is refused (None if it is graded): a submission is a subdirectory
    or a .tar.gz/.tgz/.zip file with a safe name. Every other entry is
    refused, so that it gets a row of its own and nothing is left out
    without the instructor seeing it; a link is never followed (it could
    name any file the grader can read)."""
    found = []
    for entry in sorted(os.listdir(directory)):
        full = os.path.join(directory, entry)
        name = ARCHIVE_SUFFIX.sub('', entry)
        if os.path.islink(full):
            problem = 'a link, not followed'
        elif os.path.isdir(full):
            name, problem = entry, name_problem(entry)
        elif os.path.isfile(full) and ARCHIVE_SUFFIX.search(entry):
            problem = name_problem(name)
        else:
            problem = 'neither a directory nor a .tar.gz, .tgz or .zip file'
        found.append((name, full, problem))
    # Two submissions with one name (alice/ and alice.zip) would share a
    # results directory and a student: neither is graded.
    names = [name for name, _, _ in found]
    found = [(name, full, problem or ('another submission is also named %s' % name
                                      if names.count(name) > 1 else None))
             for name, full, problem in found]
    return found


def remove_inside(out, target):
    """Removes target, an old result directory, only if its real path is
    strictly inside out's: whatever a name or a link says, nothing outside the
    batch's output is ever removed (and not the output itself)."""
    root = os.path.realpath(out)
    real = os.path.realpath(target)
    if real == root or os.path.commonpath([root, real]) != root:
        raise ValueError('%s is not inside %s: not removed' % (target, out))
    if os.path.islink(target):
        os.unlink(target)
    else:
        shutil.rmtree(target, ignore_errors=True)


METADATA = 'submission_metadata.json'


class RosterError(Exception):
    pass


ROSTER_COLUMNS = ['submission', 'student', 'login']


def read_roster(path, names):
    """{submission name: [(student, login)]} from an instructor's CSV with the
    columns submission, student, login (a header line, then a row per
    student; several rows for one submission make a group). names are the
    batch's submissions: a row naming another is an error, as is anything
    malformed; each names the file and line."""
    try:
        with open(path, encoding='utf-8-sig', newline='') as f:
            lines = list(csv.reader(f))
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        raise RosterError('%s: cannot be read as a UTF-8 CSV file (%s)' % (path, e))
    if not lines or [c.strip().lower() for c in lines[0]] != ROSTER_COLUMNS:
        raise RosterError('%s:1: the first line must be the header %s'
                          % (path, ','.join(ROSTER_COLUMNS)))
    roster, seen = {}, {}
    for number, row in enumerate(lines[1:], start=2):
        if not any(c.strip() for c in row):
            continue                       # a blank line
        where = '%s:%d: ' % (path, number)
        if len(row) != len(ROSTER_COLUMNS):
            raise RosterError(where + 'expected %d columns (%s), found %d'
                              % (len(ROSTER_COLUMNS), ','.join(ROSTER_COLUMNS), len(row)))
        submission, student, login = (c.strip() for c in row)
        if not student or not login or not submission:
            raise RosterError(where + 'submission, student and login must all be given')
        if any(not c.isprintable() for c in student + login):
            raise RosterError(where + 'a student or login holds a control character')
        if submission not in names:
            raise RosterError(where + 'there is no submission named %r in the batch'
                              % submission)
        if login in seen:
            raise RosterError(where + 'login %s is already on line %d' % (login, seen[login]))
        seen[login] = number
        roster.setdefault(submission, []).append((student, login))
    return roster


def submitters(name, path, roster):
    """([(student, login)], note) of a submission: the roster's rows for it,
    else its name for both. A submission_metadata.json inside the submission
    is the student's own file and is never believed (a student could name
    another student in it); note says that it was ignored."""
    note = None
    if os.path.isdir(path) and os.path.lexists(os.path.join(path, METADATA)):
        note = ('%s: its %s was ignored (who submitted comes from the submission\'s '
                'name or from --roster, never from a file inside the submission)'
                % (name, METADATA))
    if roster is not None and name not in roster:
        note = (note + '; ' if note else '%s: ' % name) + \
            'not in the roster: graded under its name'
    return (roster or {}).get(name) or [(name, name)], note


def csv_text(rows):
    """The CSV text of rows (csv's own quoting and line ends)."""
    text = io.StringIO()
    csv.writer(text).writerows(rows)
    return text.getvalue()


def write_gradebook(path, exercises_graded, students):
    """One row per student: Student, SIS Login ID, Section (empty), a column
    per exercise (its points), Total. Canvas matches the rows to its students
    by SIS Login ID and wants the Section column, which may be empty; Moodle
    matches by the column one maps to an identifier at import. No other rows
    (a "points possible" row would be a student that Moodle cannot find).
    students: [(student, login, {exercise: points} or None if the grader
    failed)]."""
    rows = [['Student', 'SIS Login ID', 'Section'] + [e for e, _ in exercises_graded] +
            ['Total']]
    for student, login, points in sorted(students, key=lambda s: (s[1], s[0])):
        if points is None:      # the grader failed: no number rather than a wrong one
            rows.append([student, login, ''] + [''] * (len(exercises_graded) + 1))
            continue
        values = [points.get(e, 0) for e, _ in exercises_graded]
        rows.append([student, login, ''] + ['%g' % round(v, 4) for v in values] +
                    ['%g' % round(sum(values), 4)])
    atomic_write(path, csv_text(rows))


def private_flags(flags):
    """A flags file (@FILE, one argument a line) holding flags, in a directory
    only this user can enter, removed when the grader exits. The batch gives
    its graders the secret this way: on their command lines, every process of
    the machine could read it (/proc/PID/cmdline), a student's worker in the
    fallback without namespaces too."""
    directory = tempfile.mkdtemp(prefix='lrt-batch-')
    atexit.register(shutil.rmtree, directory, True)
    path = os.path.join(directory, 'flags')
    write_private(path, ''.join(flag + '\n' for flag in flags))
    return path


def grade_batch(args):
    out = os.path.abspath(args.out or os.path.join(args.root, 'build', 'grade', 'batch'))
    found = submissions_in(args.batch)
    subs = [(name, path) for name, path, problem in found if problem is None]
    refused = [(os.path.basename(path), name, problem) for name, path, problem in found
               if problem]
    # The roster is read before anything is graded: a mistake in it stops
    # the batch while it costs nothing.
    roster = None
    if args.roster:
        try:
            roster = read_roster(args.roster, {name for name, _, _ in found})
        except RosterError as e:
            print('grade-batch: %s' % e, file=sys.stderr, flush=True)
            return 2
    os.makedirs(out, exist_ok=True)
    start = time.time()
    rows, done, broken = [], [0], []
    # The chapters are resolved once, here, so that every student is graded
    # on the same set (and a wrong --chapters stops the batch before it starts).
    _, book = load_book(args.root)
    selected = graded_exercises(book, args, args.root)   # a bad plan stops the batch here
    # Children given no choice make the same default one (the kit's
    # exercises.json, or every chapter).
    chapters = graded_chapters(book, args.chapters, args.root) if args.chapters else []
    # One secret for the whole batch: every student's code answers the same
    # cases.
    forwarded = ['--root', args.root, '--cache', args.cache, '--time-limit',
                 str(args.time_limit), '--memory-limit', str(args.memory_limit),
                 '--judge-memory-limit', str(args.judge_memory_limit),
                 '--cpu-limit', str(args.cpu_limit),
                 '--exercise-time-limit', str(args.exercise_time_limit),
                 '@' + private_flags(['--seed', str(args.secret)]),
                 '--compile-time-limit', str(args.compile_time_limit),
                 '--cxxflags', args.cxxflags, '--build-jobs', '1']
    if args.allow_no_sandbox:
        forwarded.append('--allow-no-sandbox')
    if chapters:
        forwarded += ['--chapters', ' '.join(chapters)]
    if args.plan:
        forwarded += ['--plan', os.path.abspath(args.plan), '--assignment', args.assignment]
    if args.allow_changes_outside_exercises:
        forwarded.append('--allow-changes-outside-exercises')

    identities, notes = {}, []
    for student, path in subs:
        identities[path], note = submitters(student, path, roster)
        if note:
            notes.append(note)
    # A refused submission is not graded: it gets a row with no number in
    # both CSV files, like a grader error, so that the instructor sees it
    # where the grades are. The row names it "REFUSED FILE" (or by its roster
    # rows): the file name alone could be "=..." or "-...", which a
    # spreadsheet opening the CSV takes for a formula.
    book_rows = []
    for entry, name, problem in refused:
        shown = 'REFUSED ' + printable(entry)
        rows.append((shown, '', '', '', ''))
        book_rows.extend((student, login, None) for student, login in
                         (roster or {}).get(name) or [(shown, shown)])
        print('%s: %s' % (shown, problem), flush=True)

    def one(item):
        student, path = item
        target = os.path.join(out, student)
        t0 = time.time()
        try:
            remove_inside(out, target)      # never read an old result
        except ValueError as e:
            return student, target, None, str(e), 0.0, path
        # '--' before the path: a name that looks like an option stays a path.
        code, output = grade_build.run([sys.executable, GRADE,
                                        '--out', target, '--quiet'] + forwarded +
                                       ['--', path], timeout=args.submission_time_limit)
        return student, target, code, output, time.time() - t0, path

    workers = max(1, min(2, args.workers))
    with concurrent.futures.ThreadPoolExecutor(workers) as pool:
        futures = [pool.submit(one, item) for item in subs]
        for future in concurrent.futures.as_completed(futures):
            student, target, code, output, elapsed, path = future.result()
            done[0] += 1
            try:
                if code is None:
                    raise ValueError(output)
                with open(os.path.join(target, 'results.json'), encoding='utf-8') as f:
                    data = json.load(f)
                points = {}
                for e in data['extra_data']['exercises']:
                    rows.append((student, e['chapter'], e['exercise'], e['points'],
                                 e['max_points']))
                    points[e['exercise']] = e['points']
                book_rows.extend((name, login, points) for name, login in identities[path])
                score = '%g/%g' % (data['score'], data['max_score'])
            except (OSError, ValueError, KeyError) as e:
                broken.append(student)
                rows.append((student, '', '', 0, ''))
                book_rows.extend((name, login, None) for name, login in identities[path])
                score = 'GRADER ERROR (%s): %s' % (code, first_line(output[-2000:]) or e)
            if code != 0 and student not in broken:
                broken.append(student)
                score += ' (grader exit status %s)' % code
            bar = '#' * int(30 * done[0] / max(1, len(subs)))
            print('[%-30s] %d/%d %s: %s (%.1f s)' % (bar, done[0], len(subs), student, score,
                                                     elapsed), flush=True)
    csv_path = os.path.join(out, 'grades.csv')
    atomic_write(csv_path, csv_text(
        [['student', 'chapter', 'exercise', 'points', 'max_points']] +
        sorted(rows, key=lambda r: (r[0], str(r[1]), str(r[2])))))
    # The gradebook: one row per student, the exercises in the book's order.
    gradebook = os.path.join(out, 'gradebook.csv')
    write_gradebook(gradebook, [(e.id, selected[e.id]) for e in book.exercises
                                if e.id in selected], book_rows)
    logins = [login for _, login, _ in book_rows]
    for login in sorted({x for x in logins if logins.count(x) > 1}):
        notes.append('%s is in more than one submission: check the gradebook' % login)
    for entry, _, problem in refused:
        notes.append('REFUSED %s, not graded (its rows have no number): %s; rename it '
                     'and grade it again' % (printable(entry), problem))
    for note in notes:
        print('grade-batch: ' + note, file=sys.stderr)
    totals = {}
    graded = {name for name, _ in subs}
    for student, _, _, points, _ in rows:
        if student in graded:
            totals[student] = totals.get(student, 0) + float(points or 0)
    values = sorted(totals.values())
    print('graded %d submissions in %.1f s (%d with grader errors%s)%s; scores: min %g, '
          'median %g, max %g; %s' % (len(subs), time.time() - start, len(broken),
                                    ': ' + ', '.join(broken) if broken else '',
                                    '; %d REFUSED (not graded): %s' % (
                                        len(refused), ', '.join(printable(e) for e, _, _ in
                                                                refused)) if refused else '',
                                    values[0] if values else 0,
                                    values[len(values) // 2] if values else 0,
                                    values[-1] if values else 0, csv_path))
    print('gradebook (one row per student): %s' % gradebook)
    return 0

