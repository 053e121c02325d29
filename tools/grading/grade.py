#!/usr/bin/env python3
"""Grade a student's submission with lrt's tests (DESIGN.md section 7).

    tools/grading/grade.py [options] SUBMISSION          grade one submission
    tools/grading/grade.py --batch DIR [--out DIR]       grade every submission in DIR

A submission is a directory, a .tar.gz/.tgz or a .zip holding edited chapter
files: chapters/NN-slug.md, or NN-slug.md anywhere in it. Anything else is
ignored and reported. Archives are read member by member: no member is ever
written outside the grader's own directory, links and special files are
ignored, and sizes are limited.

With --plan FILE --assignment NAME (a course plan, docs/course.md) the
assignment's exercises are graded, worth the plan's points. @FILE stands for
the arguments in FILE, one per line (Gradescope's grade_flags).

Which chapters are graded: those of --chapters ("05", "02 05"), else the
chapters a kit was built for (the exercises.json of a kit that `make
exercises CHAPTERS=...` made), else every chapter with exercises. Their
exercises make up max_score; a graded chapter missing from the submission
scores 0, and a chapter that is not graded is listed and left alone.

Each graded chapter that the submission holds is graded on its own:
the student's chapter N is tangled with the reference text of every other
chapter (chapters 1..N), compiled, and chapter N's public and hidden tests are
built. A compile error scores that chapter 0 and shows the first errors, at the
student's file and line. Every exercise test then runs in its own process
(--gtest_filter=Suite.Name), in a fresh working directory, with a time and a
memory limit. A test passes only if its own JSON report exists and says so;
an exit before the report (exit(0)), a signal, a timeout or a memory blow-up
fails that test alone, and text printed by the student's code counts for
nothing. Statuses: PASS, FAIL, CRASH (with the signal), TIMEOUT, OOM,
COMPILE-ERROR, NOT-RUN.

Points: an exercise's points are split evenly over its tests, public and
hidden (partial credit); tests that belong to no exercise are not run.

Structure: exercise chunks renamed, deleted or duplicated, and code changed
outside the solution regions are reported with the student's file:line. By
default the reference's code outside the exercises is restored (the student's
solution regions are spliced into the reference chapter; a region the student
deleted gets the stub); --allow-changes-outside-exercises grades the student's
chapter as written. Prose changes are always fine.

Outputs, in --out (default build/grade/NAME), rewritten atomically after every
test: results.json (Gradescope), junit.xml and results.txt (a plain table).
Batch mode writes OUT/NAME/ for each student, OUT/grades.csv (a row per
student and exercise) and OUT/gradebook.csv (a row per student, a column per
exercise and the total; the student from a submission directory's
submission_metadata.json, Gradescope's, else the submission's name).

The student's code is compiled and run behind a wall (docs/grading.md, "The
trust boundary"): what a region may hold (tools/grading/compile_wall.py), compiles
and workers in a sandbox or as an unprivileged user (tools/grading/sandbox.py), and
every verdict decided by the judge, which holds the tests and runs none of
the student's code.
"""
import argparse
import atexit
import concurrent.futures
import csv
import difflib
import hashlib
import io
import json
import os
import re
import secrets
import shutil
import signal
import subprocess
import sys
import tarfile
import tempfile
import time
import xml.etree.ElementTree as ET
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(os.path.dirname(HERE)))  # the repository: import tools.*
from tools.exercises import course  # noqa: E402
from tools.exercises import markup  # noqa: E402
from tools.grading import build as grade_build  # noqa: E402
from tools.grading import compile_wall  # noqa: E402
from tools.grading import sandbox  # noqa: E402

CHAPTER_NAME = re.compile(r'^(\d\d)-[^/\\]*\.md$')
MAX_FILES = 2000              # members looked at in a submission
MAX_CHAPTER_BYTES = 4 << 20   # one chapter file
MAX_TOTAL_BYTES = 64 << 20    # everything read from a submission
DEFAULT_CXXFLAGS = ' '.join(grade_build.WORKER_CXXFLAGS)  # tools/compile/flags.mk
MAX_SHOWN = 4000              # characters of a failure shown
# Failures that the judge's own code reports (a worker that crashed, hung or
# ran out of memory) name this file; of a hidden test's, their first words
# are shown (shown_message).
JUDGE_SOURCE = 'tests/calls/judge.cpp'
FIRST_ERRORS = 10


def log(message):
    print(message, file=sys.stderr, flush=True)


# ---------------------------------------------------------------------------
# Submissions

class Submission:
    """The chapter files found in a submission, and what was ignored."""
    def __init__(self):
        self.chapters = {}    # basename -> (name inside the submission, bytes)
        self.ignored = []     # (name, reason)
        self.problems = []    # messages about the submission as a whole


def safe_name(name):
    """A member name as a relative path, or None if it escapes."""
    name = name.replace('\\', '/')
    if name.startswith('/') or re.match(r'^[A-Za-z]:', name):
        return None
    parts = [p for p in name.split('/') if p not in ('', '.')]
    if not parts or '..' in parts:
        return None
    return '/'.join(parts)


def read_submission(path, reference_names):
    """Reads a submission without writing any of it to disk outside memory."""
    sub = Submission()
    entries = []   # (name, reader() -> bytes, size)  regular files only
    total = 0

    def consider(name, size, reader):
        nonlocal total
        clean = safe_name(name)
        if clean is None:
            sub.ignored.append((name, 'unsafe path (absolute or with ..): ignored'))
            return
        base = clean.rsplit('/', 1)[-1]
        if not CHAPTER_NAME.match(base):
            sub.ignored.append((clean, 'not a chapter file'))
            return
        if base not in reference_names:
            sub.ignored.append((clean, 'no chapter of the book is named %s' % base))
            return
        if size > MAX_CHAPTER_BYTES:
            sub.ignored.append((clean, 'too large (%d bytes)' % size))
            return
        if total + size > MAX_TOTAL_BYTES:
            sub.ignored.append((clean, 'the submission is too large'))
            return
        try:
            data = reader()
        except (ValueError, OSError, EOFError, zipfile.BadZipFile, tarfile.TarError,
                RuntimeError) as e:
            sub.ignored.append((clean, 'cannot be read (%s)' % e))
            return
        total += len(data)
        entries.append((clean, data))

    def reader_of(read):
        def get():
            data = read()
            if len(data) > MAX_CHAPTER_BYTES:
                raise ValueError('too large')
            return data
        return get

    if os.path.isdir(path):
        count = 0
        for top, dirs, files in os.walk(path, followlinks=False):
            dirs.sort()
            for d in list(dirs):
                if os.path.islink(os.path.join(top, d)):
                    sub.ignored.append((os.path.relpath(os.path.join(top, d), path),
                                        'a symbolic link: ignored'))
                    dirs.remove(d)
            for f in sorted(files):
                full = os.path.join(top, f)
                rel = os.path.relpath(full, path)
                count += 1
                if count > MAX_FILES:
                    sub.problems.append('more than %d files: the rest is ignored' % MAX_FILES)
                    break
                if os.path.islink(full) or not os.path.isfile(full):
                    sub.ignored.append((rel, 'not a regular file (a link?): ignored'))
                    continue

                def read(full=full):
                    with open(full, 'rb') as fh:
                        return fh.read(MAX_CHAPTER_BYTES + 1)
                consider(rel, os.path.getsize(full), reader_of(read))
    elif zipfile.is_zipfile(path):
        try:
            with zipfile.ZipFile(path) as z:
                for count, info in enumerate(z.infolist()):
                    if count >= MAX_FILES:
                        sub.problems.append('more than %d files: the rest is ignored'
                                            % MAX_FILES)
                        break
                    if info.is_dir():
                        continue
                    mode = (info.external_attr >> 16) & 0o170000
                    if mode and mode != 0o100000:
                        sub.ignored.append((info.filename, 'not a regular file (a link?): '
                                            'ignored'))
                        continue
                    consider(info.filename, info.file_size, reader_of(
                        lambda info=info: z.open(info).read(MAX_CHAPTER_BYTES + 1)))
        except (zipfile.BadZipFile, OSError, EOFError, RuntimeError) as e:
            sub.problems.append('the archive is damaged: %s' % e)
    elif tarfile.is_tarfile(path):
        try:
            with tarfile.open(path) as t:
                for count, member in enumerate(t):
                    if count >= MAX_FILES:
                        sub.problems.append('more than %d files: the rest is ignored'
                                            % MAX_FILES)
                        break
                    if member.isdir():
                        continue
                    if not member.isfile():
                        sub.ignored.append((member.name, 'not a regular file (a link?): '
                                            'ignored'))
                        continue
                    consider(member.name, member.size, reader_of(
                        lambda m=member: t.extractfile(m).read(MAX_CHAPTER_BYTES + 1)))
        except (tarfile.TarError, OSError, EOFError) as e:
            sub.problems.append('the archive is damaged: %s' % e)
    else:
        sub.problems.append('%s is neither a directory nor a .tar.gz or .zip archive'
                            % os.path.basename(path))
    # One file per chapter: chapters/NN-slug.md first, then the shortest path.
    by_base = {}
    for name, data in entries:
        by_base.setdefault(name.rsplit('/', 1)[-1], []).append((name, data))
    for base, found in sorted(by_base.items()):
        found.sort(key=lambda e: (not (e[0] == 'chapters/' + base or
                                       e[0].endswith('/chapters/' + base)),
                                  e[0].count('/'), e[0]))
        name, data = found[0]
        sub.chapters[base] = (name, data)
        for other, _ in found[1:]:
            sub.ignored.append((other, 'another copy of %s; graded %s' % (base, name)))
    return sub


# ---------------------------------------------------------------------------
# Structure: the student's chunks against the reference's

def parse_chapter(path):
    book = markup.Book([path], tests=False)
    return book.chapters[0], book


def skeleton(chunk, regions):
    """A chunk's body with each solution region (and stub block) replaced by
    one placeholder line; trailing blanks ignored."""
    out, i, by_begin = [], 0, {r.begin: r for r in regions}
    body = chunk.body
    while i < len(body):
        region = by_begin.get(i)
        if region is not None:
            out.append('\0REGION')
            i = (region.stub_end if region.stub_end is not None else region.end) + 1
            continue
        out.append(body[i].rstrip())
        i += 1
    while out and not out[-1]:
        out.pop()
    return tuple(out)


def chunk_regions(chunk):
    regions, errors = markup.find_regions(chunk.body)
    for region in regions:
        region.chunk = region.path = chunk
    return regions, errors


def check_structure(reference, student, student_name, allow=False):
    """Compares two parsed chapters. Returns (problems, code_changed, plan):
    problems are messages; plan maps each reference region to the student's
    region lines ((line, text) list) or None (deleted: use the stub)."""
    problems = []
    not_done = '' if allow else ': graded as not done'
    exercise_chunks = {f: e for e in reference.exercises for f in e.fragments}
    ref_names = [c.name for c in reference.chunks]
    stu_names = [c.name for c in student.chunks]
    stu_regions = {}
    for chunk in student.chunks:
        regions, errors = chunk_regions(chunk)
        for index, message in errors:
            problems.append('%s:%d: in <<%s>>: %s' % (student_name, chunk.line + 1 + index,
                                                       chunk.name, message))
        stu_regions[id(chunk)] = regions
    new_names = [n for n in dict.fromkeys(stu_names) if n not in ref_names]
    for name, exercise in exercise_chunks.items():
        want = ref_names.count(name)
        have = [c for c in student.chunks if c.name == name]
        if not have:
            guess = [n for n in new_names]
            first = [c for c in reference.chunks if c.name == name][0]
            ref_skel = skeleton(first, [r for r in reference.regions if r.chunk is first])
            renamed = [c for c in student.chunks if c.name in new_names and
                       skeleton(c, stu_regions[id(c)]) == ref_skel]
            if renamed:
                problems.append('%s:%d: exercise chunk <<%s>> (%s) was renamed to <<%s>>%s'
                                % (student_name, renamed[0].line, name, exercise.id,
                                   renamed[0].name, not_done))
            else:
                problems.append('%s: exercise chunk <<%s>> (%s) was deleted%s%s'
                                % (student_name, name, exercise.id,
                                   ' or renamed (new chunks: %s)' % ', '.join(
                                       '<<%s>>' % g for g in guess) if guess else '',
                                   not_done))
        elif len(have) > want:
            problems.append('%s:%d: exercise chunk <<%s>> (%s) is defined %d times (lines '
                            '%s); the book defines it %d time(s)%s'
                            % (student_name, have[want].line, name, exercise.id, len(have),
                               ', '.join(str(c.line) for c in have), want,
                               '' if allow else ': only the first is graded'))
    # The code outside the solution regions, chunk by chunk.
    ref_seq = [(c.name, skeleton(c, [r for r in reference.regions if r.chunk is c]))
               for c in reference.chunks]
    stu_seq = [(c.name, skeleton(c, stu_regions[id(c)])) for c in student.chunks]
    changes = []
    matcher = difflib.SequenceMatcher(None, ref_seq, stu_seq, autojunk=False)
    for tag, i1, i2, j1, j2 in matcher.get_opcodes():
        if tag == 'equal':
            continue
        ref_part, stu_part = reference.chunks[i1:i2], student.chunks[j1:j2]
        stu_by_name = {}
        for c in stu_part:
            stu_by_name.setdefault(c.name, []).append(c)
        for c in ref_part:
            same = stu_by_name.get(c.name)
            if same:
                s = same.pop(0)
                changes.append('%s:%d: the code of <<%s>> differs from the book\'s '
                               '(outside the solution regions)' % (student_name, s.line,
                                                                   c.name))
            else:
                changes.append('%s: chunk <<%s>> (book line %d) is missing'
                               % (student_name, c.name, c.line))
        for name, rest in stu_by_name.items():
            for s in rest:
                changes.append('%s:%d: chunk <<%s>> is %s' % (
                    student_name, s.line, name, 'an extra definition' if name in ref_names
                    else 'not in the book'))
    # Which student region fills which reference region: the k-th region of
    # chunk name X in the student's text fills the k-th of the reference's.
    plan = {}
    for name in dict.fromkeys(ref_names):
        ref_r = [r for r in reference.regions if r.chunk.name == name]
        stu_r = [r for c in student.chunks if c.name == name for r in stu_regions[id(c)]]
        for k, region in enumerate(ref_r):
            if k < len(stu_r):
                s = stu_r[k]
                plan[id(region)] = [(s.line(i), s.chunk.body[i])
                                    for i in range(s.begin + 1, s.end)]
            else:
                plan[id(region)] = None
                if name not in exercise_chunks or [c for c in student.chunks
                                                   if c.name == name]:
                    problems.append('%s: the solution region %d of <<%s>> is missing '
                                    '(BEGIN/END SOLUTION markers removed?): graded as '
                                    'not done' % (student_name, k + 1, name))
        if len(stu_r) > len(ref_r):
            extra = stu_r[len(ref_r)]
            problems.append('%s:%d: <<%s>> has %d solution regions; the book has %d: the '
                            'extra ones are not graded' % (student_name,
                                                           extra.line(extra.begin),
                                                           name, len(stu_r), len(ref_r)))
    return problems, changes, plan


def compose(base, base_name, fills):
    """The chapter `base` (parsed) with some of its solution regions filled
    anew: fills maps a region of base to the lines (file, line, text) to put
    between its markers; other regions stay as they are. A filled region's
    stub block is dropped. Returns (text, line map: output line -> (file, line))."""
    starts = {r.line(r.begin): r for r in base.regions if r in fills}
    lines, where = [], []
    n = 1
    while n <= len(base.lines):
        region = starts.get(n)
        if region is None:
            lines.append(base.lines[n - 1])
            where.append((base_name, n))
            n += 1
            continue
        lines.append(base.lines[n - 1])        # // BEGIN SOLUTION
        where.append((base_name, n))
        for name, line, text in fills[region]:
            lines.append(text)
            where.append((name, line))
        end = region.line(region.end)
        lines.append(base.lines[end - 1])      # // END SOLUTION
        where.append((base_name, end))
        n = (region.line(region.stub_end) if region.stub_end is not None else end) + 1
    return '\n'.join(lines) + '\n', where


def exercise_text(reference, student, plan, exercise, student_name, allow):
    """Chapter text for grading `exercise` alone: the student's code for its
    regions, the book's solutions for every other exercise's. By default the
    book's text is the base (code the student changed outside the regions is
    not used); with `allow` (--allow-changes-outside-exercises), the
    student's. A region the student deleted gets the stub."""
    mine = set(exercise.fragments)
    if not allow:
        fills = {}
        for region in reference.regions:
            if region.chunk.name not in mine:
                continue
            filled = plan.get(id(region))
            if filled is None:
                fills[region] = [(reference.path + ' (stub)', region.line(region.begin), t)
                                 for t in markup.stub_code(region)]
            else:
                fills[region] = [(student_name, line, t) for line, t in filled]
        return compose(reference, reference.path, fills)
    # The student's chapter, with the k-th region of each chunk name that
    # belongs to another exercise replaced by the book's k-th.
    fills, seen = {}, {}
    for region in student.regions:
        name = region.chunk.name
        k = seen.get(name, 0)
        seen[name] = k + 1
        if name in mine:
            continue
        ref = [r for r in reference.regions if r.chunk.name == name]
        if k < len(ref):
            fills[region] = [(reference.path, line, t) for line, t in ref[k].solution]
    return compose(student, student_name, fills)


# ---------------------------------------------------------------------------
# Building and judging

def region_lines(regions):
    """The chapter's line numbers of the regions, markers and stubs included."""
    return {n for r in regions
            for n in range(r.line(r.begin), r.line(r.stub_end if r.stub_end is not None
                                                   else r.end) + 1)}


# A diagnostic at a line of the book's solution of another exercise (the
# student's code can cause one there: a name it declares that the book's code
# then uses) is shown as this, without its words, which may quote that code.
HIDDEN_DIAGNOSTIC = ('error in the book\'s code of another exercise, which is not shown '
                     '(caused by your code: check the names you declare)')
LOCATION = re.compile(r'^(.*?):(\d+):(?:(\d+):)? ')


def compiler_errors(output, rename):
    """The first error lines of a build, with paths rewritten by rename
    (None: a line whose diagnostics are not shown); each error once (a
    header's error repeats in every file that includes it)."""
    found = []
    lines = output.splitlines()
    for i, line in enumerate(lines):
        m = re.match(r'^(.*?):(\d+):(?:(\d+):)? (fatal error|error): (.*)$', line)
        if m:
            where = rename(m.group(1), int(m.group(2)), m.group(3))
            text = (where + ': error: ' + m.group(5) if where is not None
                    else HIDDEN_DIAGNOSTIC)
        elif 'undefined reference to' in line:
            text = 'link error: ' + line.split(': ', 1)[-1]
        elif line.startswith('tangle: '):
            # the tangle's own message, and notangle's lines after it
            text = '\n'.join([line] + [x for x in lines[i + 1:i + 6]
                                       if x.strip() and not x.startswith(('make', '\t'))])
        else:
            continue
        if text not in found:
            found.append(text)
        if len(found) >= FIRST_ERRORS:
            break
    return found


def shown_output(lines, rename):
    """A build's last lines, where no error line was found, as the student
    may see them: a line at a location whose diagnostics are not shown
    becomes HIDDEN_DIAGNOSTIC. The compiler prints no source lines
    (-fdiagnostics-plain-output), so only a diagnostic's own words are left."""
    shown = []
    for line in lines:
        m = LOCATION.match(line)
        if m and rename(m.group(1), int(m.group(2)), m.group(3)) is None:
            line = HIDDEN_DIAGNOSTIC
        if line not in shown:
            shown.append(line)
    return shown


def signal_name(number):
    try:
        return signal.Signals(number).name
    except ValueError:
        return 'signal %d' % number


def judge_exercise(args, judge, worker, results, secret):
    """Runs the judge on the tests of one exercise (results) against its
    worker, and fills in their statuses from the judge's own report. The
    verdicts of a judge and a worker (both named by their contents in the
    cache) on the same cases are the same: they are kept, and a submission
    whose code for the exercise is the same as an earlier one's gets them
    without running again (except timeouts, which depend on the machine)."""
    key = hashlib.sha256('\0'.join([judge, worker, str(secret), repr(args.time_limit),
                                     str(args.memory_limit), str(args.cpu_limit)] +
                                    [r.full for r in results]).encode()).hexdigest()[:32]
    kept = os.path.join(args.cache, 'verdicts-%s.json' % key)
    try:
        with open(kept, encoding='utf-8') as f:
            for r, (status, failures, threw) in zip(results, json.load(f)):
                r.status, r.failures, r.threw = status, failures, threw
                r.message = '\n'.join(failures)
        return
    except (OSError, ValueError, TypeError):
        pass
    run_judge(args, judge, worker, results, secret)
    if all(r.status in ('PASS', 'FAIL', 'CRASH', 'OOM') for r in results):
        atomic_write(kept, json.dumps([[r.status, r.failures, r.threw] for r in results]))


def read_report(path):
    """{test: its line} from the judge's report, a line of JSON per test. A
    line that cannot be read (the judge stopped in the middle of it) costs
    its own test only: that test has no verdict, the others keep theirs."""
    found = {}
    try:
        with open(path, 'rb') as f:
            lines = f.readlines()
    except OSError:
        return found
    for line in lines:
        try:
            test = json.loads(line.decode('utf-8'))
            found[str(test['test'])] = test
        except (ValueError, KeyError, TypeError):
            continue
    return found


def run_judge(args, judge, worker, results, secret):
    """Runs the judge on the tests of one exercise against its worker: the
    public tests first, then the hidden ones, in two runs of the judge, each
    with workers of its own, sharing the exercise's time. A worker sees the
    arguments of every call it answers, and a public test's failure is shown
    in full, with what the code threw: so the worker that answers public
    tests must never see a hidden test's arguments, or it could keep them and
    throw them in a later call (a hidden test's failure shows nothing the code
    chose, shown_message)."""
    with tempfile.TemporaryDirectory(prefix='lrt-judge-') as tmp, \
            tempfile.TemporaryDirectory(prefix='lrt-worker-') as shared:
        # The sandbox's user must reach the binary, whatever the cache's
        # directories allow: a directory of its own that holds nothing else.
        os.chmod(shared, 0o755)
        binary = os.path.join(shared, 'worker')
        shutil.copy(worker, binary)
        os.chmod(binary, 0o755)
        argv_file = os.path.join(tmp, 'worker.argv')
        with open(argv_file, 'w') as f:
            f.write('\n'.join(sandbox.worker_command(
                binary, memory_mb=args.memory_limit, cpu_seconds=args.cpu_limit)) + '\n')
        # The secret goes to the judge in a file in this directory, which only
        # the grader's user can enter (mkdtemp's 0700), and never on a command
        # line or in an environment: any process of the machine can read
        # /proc/PID/cmdline, a student's worker or compile too where the
        # sandbox has no namespaces. The judge sets GoogleTest's shuffle seed
        # from it itself (tests/calls/judge.cpp).
        secret_file = os.path.join(tmp, 'secret')
        write_private(secret_file, '%d\n' % secret)
        deadline = time.monotonic() + args.exercise_time_limit
        for part in ('public', 'hidden'):
            tests = [r for r in results if r.hidden == (part == 'hidden')]
            if tests:
                judge_tests(args, judge, argv_file, secret_file, os.path.join(tmp, part),
                            tests, deadline)


def judge_tests(args, judge, argv_file, secret_file, base, results, deadline):
    """One run of the judge, on the tests `results` (their names go in a
    file too: a worker that read them on the judge's command line would know
    which tests it answers), until the exercise's deadline; fills in their
    statuses from the judge's report."""
    tests_file, report = base + '.tests', base + '.results.jsonl'
    with open(tests_file, 'w') as f:
        f.write(''.join(r.full + '\n' for r in results))
    cmd = [judge, '--lrt-worker=' + argv_file, '--lrt-secret-file=' + secret_file,
           '--lrt-tests-file=' + tests_file, '--lrt-call-timeout=%g' % args.time_limit,
           '--lrt-worker-log=' + base + '.worker.log', '--lrt-results=' + report]
    ended = 'the exercise took longer than %d s in all' % args.exercise_time_limit
    left = deadline - time.monotonic()
    if left > 0:
        try:
            proc = subprocess.run(cmd, stdin=subprocess.DEVNULL, capture_output=True,
                                  timeout=left, start_new_session=True)
            ended = None if proc.returncode in (0, 1) else \
                'the judge ended with status %d' % proc.returncode
        except subprocess.TimeoutExpired:
            pass
    found = read_report(report)
    for r in results:
        test = found.get(r.full)
        if test is None:
            r.status = 'NOT-RUN' if ended is None else 'TIMEOUT'
            r.message = ended or 'the judge has no test %s' % r.full
            continue
        r.failures = [str(f) for f in test.get('failures') or []]
        threw = test.get('threw')
        r.threw = threw if isinstance(threw, str) else ''
        if test.get('status') in ('CRASH', 'TIMEOUT', 'OOM'):
            r.status = test['status']
        else:
            r.status = 'PASS' if test.get('passed') is True and not r.failures else 'FAIL'
        r.message = '\n'.join(r.failures)


# ---------------------------------------------------------------------------
# Results: results.json (Gradescope), junit.xml, results.txt

class Result:
    def __init__(self, exercise, chapter, suite, name, hidden, max_score, hint):
        self.exercise, self.chapter = exercise, chapter
        self.suite, self.name, self.hidden = suite, name, hidden
        self.max_score, self.hint = max_score, hint
        self.status, self.message = 'NOT-RUN', 'not run yet'
        self.failures = []   # the judge's failure messages
        self.threw = ''      # the call whose exception failed the test
        # The messages of the exercise's own stubs, which a hidden test's
        # failure may show (shown_message).
        self.stubs = frozenset()

    @property
    def full(self):
        return '%s.%s' % (self.suite, self.name)

    @property
    def score(self):
        return self.max_score if self.status == 'PASS' else 0.0


def first_line(text):
    m = re.search(r'C\+\+ exception with description "(.*?)" thrown', text or '', re.S)
    if m:
        return ('threw: ' + ' '.join(m.group(1).split()))[:160]
    lines = [line.strip() for line in (text or '').splitlines()
             if line.strip() and line.strip() != 'unknown file']
    if len(lines) > 1 and re.match(r'^\S+:\d+$', lines[0]):   # gtest's file:line
        return ('%s: %s' % (lines[0], lines[1]))[:160]
    return lines[0][:160] if lines else ''


def fence_safe(text):
    """Text that cannot close the Markdown code block it is shown in."""
    return text.replace('`' * 3, '` ` `')


def write_private(path, text):
    """Writes text to a new file at path that only this user may read (a
    secret: a file of that name already there is an error, not followed)."""
    with open(os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600), 'w') as f:
        f.write(text)


def atomic_write(path, text):
    """Writes path whole or not at all: a temporary file beside it, renamed
    over it. The temporary file's name is new and random and it is created
    exclusively, so that no link planted in the directory under a name
    guessed in advance can turn the write to a file elsewhere."""
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(path) or '.',
                               prefix='.' + os.path.basename(path) + '.')
    try:
        with os.fdopen(fd, 'w', encoding='utf-8', newline='') as f:
            f.write(text)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def clean(text, limit=MAX_SHOWN):
    """Text that may come from the student's code (what it threw), as it is
    shown: printable, and not too long."""
    text = re.sub(r'[^\x20-\x7e\n\t\u00a0-\uffff]', '?', text or '')
    return text if len(text) <= limit else text[:limit] + ' [...]'


# The judge's words on a call that failed in the worker, as the judge's
# failure reads them: "tests/calls/judge.cpp:LINE", GoogleTest's "Failed",
# then "during Call: KIND: DETAIL" (tests/calls/judge.cpp, Kind). Of a hidden
# test, only "during Call: KIND" is shown: the detail is the code's to choose.
# Matched from the start: the first "during" is the judge's own.
WORKER_FAILURE = re.compile(r'%s:\d+\n(?:Failed\n)?(during [A-Za-z_]\w*: (?:the code crashed|'
                            r'the code took too long|the code ran out of memory|the answer '
                            r'was refused))(?=:|$)' % re.escape(JUDGE_SOURCE), re.M)
THROWN = re.compile(r'C\+\+ exception with description "(.*?)" thrown', re.S)
HIDDEN_CHECK = 'a hidden test failed (its checks are not shown)'


def shown_message(result):
    """What a student may see of a test's failure: everything for a public
    test. A hidden test's worker saw the test's inputs, so what a student
    sees of its failure holds nothing that the student's code chose, which
    could carry them: never the test's checks (the values the code returned)
    nor what the code threw, a signal or an exit status, only the kind of
    failure (the code threw, crashed, took too long, ran out of memory) and
    the call, whose name is public. Only the message of one of the
    exercise's own stubs is shown as thrown: an unfinished exercise says so,
    and the code can choose no more than which stub it throws."""
    if not result.hidden or not result.failures:
        return clean(result.message)
    call = result.threw if re.fullmatch(r'[A-Za-z_]\w*', result.threw or '') else ''
    shown = []
    for failure in result.failures:
        thrown = THROWN.search(failure)
        worker = WORKER_FAILURE.match(failure)
        if thrown and thrown.group(1) in result.stubs:
            text = 'threw: ' + thrown.group(1)
        elif thrown:
            text = '%sthe code threw an exception (not shown for a hidden test)' % (
                'during %s: ' % call if call else '')
        elif worker:
            text = worker.group(1)
        else:
            text = HIDDEN_CHECK
        if text not in shown:
            shown.append(text)
    return clean('\n'.join(shown))


class Report:
    def __init__(self, out, sub_label):
        self.out, self.label = out, sub_label
        self.results = []
        self.notes = []        # Markdown lines for the top-level output
        self.exercises = []    # (chapter, exercise id, points)
        self.failed = False    # the grader itself failed somewhere
        self.secret = None     # of the random cases, to repeat a grading (--seed)
        os.makedirs(out, exist_ok=True)

    def exercise_scores(self):
        rows = []
        for chapter, ident, points in self.exercises:
            rs = [r for r in self.results if r.exercise == ident]
            got = sum(r.score for r in rs)
            statuses = sorted({r.status for r in rs})
            rows.append((chapter, ident, round(got, 4), points, statuses))
        return rows

    def write(self):
        total = sum(r.score for r in self.results)
        maximum = sum(p for _, _, p in self.exercises)
        tests = []
        for number, r in enumerate(self.results, 1):
            message = shown_message(r)
            md = ['**%s**%s' % (r.status, ' (hidden test)' if r.hidden else '')]
            if message:
                md.append('```\n%s\n```' % fence_safe(message))
            if r.status != 'PASS' and r.hint:
                md.append('Hint: ' + r.hint)
            tests.append({'name': '%s %s' % (r.exercise, r.full),
                          'number': '%s.%d' % (r.exercise[len('ex-'):], number),
                          'score': round(r.score, 4), 'max_score': round(r.max_score, 4),
                          'status': 'passed' if r.status == 'PASS' else 'failed',
                          'output': '\n\n'.join(md), 'output_format': 'md',
                          'visibility': 'after_published' if r.hidden else 'visible',
                          'tags': [r.status]})
        data = {'score': round(total, 4), 'max_score': maximum,
                'output': '\n'.join(self.notes) or 'Graded.', 'output_format': 'md',
                'stdout_visibility': 'hidden', 'visibility': 'visible', 'tests': tests,
                'extra_data': {'submission': self.label, 'secret': self.secret,
                               'exercises': [
                    {'chapter': c, 'exercise': i, 'points': g, 'max_points': p,
                     'statuses': s} for c, i, g, p, s in self.exercise_scores()]}}
        atomic_write(os.path.join(self.out, 'results.json'), json.dumps(data, indent=1))
        atomic_write(os.path.join(self.out, 'junit.xml'), self.junit())
        atomic_write(os.path.join(self.out, 'results.txt'), self.table(total, maximum))

    def junit(self):
        suites = ET.Element('testsuites', name='lrt grading: ' + self.label)
        for chapter, ident, got, points, _ in self.exercise_scores():
            rs = [r for r in self.results if r.exercise == ident]
            suite = ET.SubElement(suites, 'testsuite', name=ident, tests=str(len(rs)),
                                  failures=str(sum(r.status == 'FAIL' for r in rs)),
                                  errors=str(sum(r.status not in ('PASS', 'FAIL', 'NOT-RUN')
                                                 for r in rs)),
                                  skipped=str(sum(r.status == 'NOT-RUN' for r in rs)))
            for r in rs:
                case = ET.SubElement(suite, 'testcase', classname='%s.%s' % (ident, r.suite),
                                     name=r.name)
                if r.status == 'FAIL':
                    ET.SubElement(case, 'failure', message=first_line(shown_message(r)),
                                  type='FAIL').text = shown_message(r)
                elif r.status == 'NOT-RUN':
                    ET.SubElement(case, 'skipped', message=first_line(r.message))
                elif r.status != 'PASS':
                    ET.SubElement(case, 'error', message=first_line(shown_message(r)),
                                  type=r.status).text = shown_message(r)
        return ET.tostring(suites, encoding='unicode') + '\n'

    def table(self, total, maximum):
        lines = ['Submission: %s' % self.label, '']
        lines += [re.sub(r'[`*]', '', n) for n in self.notes]
        if self.notes:
            lines.append('')
        for chapter, ident, got, points, statuses in self.exercise_scores():
            lines.append('chapter %s  %-8s %6.2f / %g' % (chapter, ident, got, points))
            for r in (r for r in self.results if r.exercise == ident):
                lines.append('    %-13s %5.2f/%-5.2f %s%s  %s' % (
                    r.status, r.score, r.max_score, r.full, ' (hidden)' if r.hidden else '',
                    first_line(shown_message(r))))
        lines += ['', 'total %.2f / %g' % (total, maximum)]
        return '\n'.join(lines) + '\n'


# ---------------------------------------------------------------------------
# Grading one submission

def hint_text(exercise, lines):
    if exercise.hint is None:
        return ''
    kind, n = exercise.hint
    if kind == 'attribute':
        parsed = markup.parse_attributes(
            re.sub(r'^:+\s*\{|\}\s*$', '', lines[exercise.line - 1].strip()))
        return (parsed[2].get('hint', '') if parsed else '').strip()
    out = []
    for text in lines[n:]:
        if re.match(r'^:{3,}\s*$', text):
            break
        out.append(text.strip())
    return ' '.join(t for t in out if t)


def load_book(root):
    """The reference book: (chapter paths relative to root, markup.Book)."""
    ref_paths = sorted(os.path.join('chapters', f) for f in os.listdir(
        os.path.join(root, 'chapters')) if CHAPTER_NAME.match(f))
    cwd = os.getcwd()
    os.chdir(root)
    try:
        book = markup.load(ref_paths, root=root)
    finally:
        os.chdir(cwd)
    if book.errors:
        raise SystemExit('grade: the reference book has exercise errors:\n' +
                         '\n'.join(book.errors))
    return ref_paths, book


def graded_chapters(book, requested, root):
    """The numbers of the chapters to grade: those requested (--chapters), else
    the chapters a kit was built for (its exercises.json), else every chapter
    with exercises. A requested chapter must exist and have exercises."""
    with_exercises = [c.number for c in book.chapters if c.exercises]
    if requested:
        numbers = [c.number for c in book.chapters]
        chosen = []
        for word in re.split(r'[\s,]+', ' '.join(requested).strip()):
            match = re.match(r'^(?:.*/)?(\d{1,2})(?:-[^/]*\.md)?$', word)
            if not match:
                raise SystemExit('grade: --chapters names chapters by number ("02 05"), '
                                 'not %r' % word)
            number = '%02d' % int(match.group(1))
            if number not in numbers:
                raise SystemExit('grade: there is no chapter %s (chapters: %s)'
                                 % (number, ' '.join(numbers)))
            if number not in with_exercises:
                raise SystemExit('grade: chapter %s has no exercises (chapters with '
                                 'exercises: %s)' % (number, ' '.join(with_exercises)))
            chosen.append(number)
        return sorted(set(chosen))
    manifest = os.path.join(root, 'exercises.json')
    if os.path.isfile(manifest):
        try:
            with open(manifest, encoding='utf-8') as f:
                kit = json.load(f)['chosen_chapters']
        except (OSError, ValueError, KeyError, TypeError) as e:
            raise SystemExit('grade: %s cannot be read (%s): give --chapters'
                             % (manifest, e))
        return [n for n in with_exercises if n in kit]
    return with_exercises


def graded_exercises(book, args, root):
    """{exercise id: points} of what is graded: the exercises of --assignment
    in --plan, with the plan's points; else those of graded_chapters()."""
    if args.plan:
        if args.chapters:
            raise SystemExit('grade: give --chapters or --plan, not both')
        if not args.assignment:
            raise SystemExit('grade: --plan needs --assignment NAME')
        try:
            plan = course.load(args.plan, {e.id: e.points for e in book.exercises})
            return dict(plan.assignment(args.assignment).points)
        except course.PlanError as e:
            raise SystemExit('grade: %s' % e)
    if args.assignment:
        raise SystemExit('grade: --assignment needs --plan FILE')
    if not args.chapters:
        manifest = os.path.join(root, 'exercises.json')
        try:
            with open(manifest, encoding='utf-8') as f:
                kit = json.load(f)
        except OSError:
            kit = {}
        except ValueError as e:
            raise SystemExit('grade: %s cannot be read (%s): give --chapters'
                             % (manifest, e))
        if isinstance(kit, dict) and kit.get('assignment'):
            # The kit of an assignment of a plan: its exercises and points.
            return {e['id']: e['points'] for e in kit['exercises']}
    numbers = graded_chapters(book, args.chapters, root)
    return {e.id: e.points for c in book.chapters if c.number in numbers
            for e in c.exercises}


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
        notes += ['- ' + p for p in problems] + ['- ' + c for c in changes]
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


# ---------------------------------------------------------------------------
# Batch mode

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


def printable(name):
    """A file name as it can be shown on one line (control characters escaped)."""
    return ''.join(c if c.isprintable() else c.encode('unicode_escape').decode('ascii')
                   for c in name)


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
            log('grade-batch: %s' % e)
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
        code, output = grade_build.run([sys.executable, os.path.abspath(__file__),
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
    report = grade(args, os.path.abspath(args.submission), out)
    if not args.quiet:
        with open(os.path.join(out, 'results.txt'), encoding='utf-8') as f:
            sys.stdout.write(f.read())
        print('results: %s' % os.path.join(out, 'results.json'))
    return 1 if report.failed else 0


if __name__ == '__main__':
    sys.exit(main())
