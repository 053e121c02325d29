"""Tests of the classroom grader (tools/grading/grade.py, docs/grading.md).

Submissions are made from chapters/05-slab-test.md (three exercises, 7
points) by text edits, in a temporary directory, and graded as one batch (two
workers, one shared build cache, so each distinct code is compiled once) by a
scratch copy of the repository; each test then asserts the exact scores and
statuses in that submission's results.json.

Two kinds of submission:

- Mistakes a student makes: the solutions (a zip), the untouched student
  edition, two exercises of three done, a compile error in one exercise's
  region (also in a spliced chapter), segfault / abort / exception, infinite
  loop / huge allocation / exit(0), fake "[  PASSED  ]" output, a wrong
  answer (the hidden tests' checks must not show), renamed, deleted and
  duplicated exercise chunks, code changed outside the exercises (restored;
  and with --allow-changes-outside-exercises), an empty submission.
- Attacks (tests/tools/attacks.py): a forged report, a killed grader, a
  process that escapes and rewrites results later, writes into the
  repository, the cache and /tmp, the hidden tests printed into the feedback
  (at run time, and at compile time with #include and .incbin), answers that
  depend on the test's name, a fork bomb, a 20 GB allocation, an archive
  whose members try to replace tests or escape with `..` and links. Each is
  put into ex-5.10's region and then fails as the stub does: the exact score
  is 5 of 7 (ex-5.9 and ex-5.11 solved), and nothing outside the results
  changes, also seconds after the grader has finished: no file of the copy
  they aim at, of the submissions, of the real repository's tests, tools and
  chapters or of what git tracks there, and no entry that the cache held
  before the batch.

The expectations come from the book, not from the grader: the exercises and
their points from `tools/exercises/markup.py list --json` (checked against the
exercise divs' own `points=`), each exercise's tests from a scan of the test
sources. The batch grades every chapter with exercises (`--chapters`, given
explicitly), so the chapters other than 5 are in max_score and their tests
are NOT-RUN.
"""
import contextlib
import csv
import hashlib
import io
import json
import os
import re
import shutil
import subprocess
import sys
import tarfile
import tempfile
import threading
import time
import unittest
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import attacks  # noqa: E402

GRADE = os.path.join(ROOT, 'tools', 'grading', 'grade.py')
CHAPTER = 'chapters/05-slab-test.md'
F9 = 'Compute the reciprocal direction and its sign on axis i'
F10 = 'Look up the reciprocal direction and its sign on axis i'
F11 = ('Widen tFar to cover rounding error', "Widen the ray's extent to cover rounding error")
TIME_LIMIT = 2
# What a student sees of a hidden test that failed a check (Hint aside).
HIDDEN_FAIL = '**FAIL** (hidden test)\n\n```\na hidden test failed (its checks are not shown)\n```'

# Read independently of tools/exercises/markup.py, which the grader uses.
TEST_LINE = re.compile(r'^\s*(?:TEST|TEST_F|TEST_P|EXERCISE_TEST)\s*\(\s*(\w+)\s*,\s*(\w+)\s*\)')
EXERCISE_SUITE = re.compile(r'^Ex(\d+)_(\d+)_\w+$')
EXERCISE_DIV = re.compile(r'^:{3,}\s*\{\.exercise\s+#(ex-\d+\.\d+)\s.*\bpoints=(\d+)')
CHAPTER_FILE = re.compile(r'^(\d\d)-.*\.md$')


def read(path):
    with open(path, encoding='utf-8') as f:
        return f.read()


def chapter_files():
    return sorted('chapters/' + f for f in os.listdir(os.path.join(ROOT, 'chapters'))
                  if CHAPTER_FILE.match(f))


def book_exercises():
    """{exercise id: its entry of `tools/exercises/markup.py list --json`}."""
    out = subprocess.run([sys.executable, os.path.join(ROOT, 'tools', 'exercises', 'markup.py'),
                          'list', '--json'] + chapter_files(), cwd=ROOT,
                         capture_output=True, text=True, check=True).stdout
    return {e['id']: e for e in json.loads(out)}


def div_points():
    """{exercise id: points} from the exercise divs of the chapters."""
    found = {}
    for path in chapter_files():
        for line in read(os.path.join(ROOT, path)).split('\n'):
            m = EXERCISE_DIV.match(line)
            if m:
                found[m.group(1)] = int(m.group(2))
    return found


def test_sources(number, hidden):
    d = os.path.join(ROOT, 'tests', 'hidden' if hidden else '', 'ch' + number)
    return sorted(os.path.join(d, f) for f in os.listdir(d)
                  if f.endswith(('.cpp', '.cc', '.h'))) if os.path.isdir(d) else []


def exercise_tests(numbers):
    """{exercise id: [(Suite.Name, hidden)]} from the test lines of the test
    sources of the given chapters."""
    found = {}
    for number in numbers:
        for hidden in (False, True):
            for path in test_sources(number, hidden):
                for line in read(path).split('\n'):
                    m = TEST_LINE.match(line)
                    e = m and EXERCISE_SUITE.match(m.group(1))
                    if e:
                        ident = 'ex-%d.%d' % (int(e.group(1)), int(e.group(2)))
                        test = ('%s.%s' % m.groups(), hidden)
                        if test not in found.setdefault(ident, []):
                            found[ident].append(test)
    return found


def hidden_only_identifiers(numbers):
    """Identifiers of the hidden tests' code (comments and strings left out)
    that occur in no chapter, public test or test name: if one shows up in a
    grade, the grader has shown a hidden test's code or failure text."""
    code = ''
    for number in numbers:
        for path in test_sources(number, True):
            text = re.sub(r'"(?:[^"\\\n]|\\.)*"', '""', read(path))
            code += re.sub(r'//[^\n]*|/\*.*?\*/', '', text, flags=re.S)
    words = set(re.findall(r'\b[A-Za-z_]\w{4,}\b', code))
    public = ''.join(read(os.path.join(ROOT, p)) for p in chapter_files())
    public += read(attacks.__file__)
    for number in numbers:
        public += ''.join(read(p) for p in test_sources(number, False))
    names = set(re.findall(r'\b\w+\b', ' '.join(
        t for tests in exercise_tests(numbers).values() for t, _ in tests)))
    return sorted(w for w in words - names if not re.search(r'\b%s\b' % w, public))


def region(text, fragment):
    """(first, last) line indexes of the solution lines of <<fragment>>."""
    lines = text.split('\n')
    start = lines.index('<<%s>>=' % fragment)
    begin = lines.index('// BEGIN SOLUTION', start)
    return begin + 1, lines.index('// END SOLUTION', begin) - 1


def inject(text, fragment, code):
    """Puts code at the start of the solution region of <<fragment>>."""
    lines = text.split('\n')
    first, _ = region(text, fragment)
    lines[first:first] = code.split('\n')
    return '\n'.join(lines)


def chapter5():
    """(owner, points): the exercise of each fragment of the book, and the
    points of chapter 5's exercises, from the book."""
    book = book_exercises()
    owner = {f: e for e, x in book.items() for f in x['fragments']}
    return owner, {e: x['points'] for e, x in book.items() if x['chapter'] == '05'}


def processes_named(name):
    """The pids of the processes whose name (comm) is name."""
    found = []
    for pid in filter(str.isdigit, os.listdir('/proc')):
        try:
            with open('/proc/%s/comm' % pid) as f:
                if f.read().strip() == name:
                    found.append(pid)
        except OSError:
            pass
    return found


def failing_bwrap(directory):
    """directory, made to hold a `bwrap` that fails as it does where a
    container forbids namespaces: first on PATH, it makes the grader fall back
    to its isolation without namespaces."""
    os.makedirs(directory)
    path = os.path.join(directory, 'bwrap')
    with open(path, 'w') as f:
        f.write('#!/bin/sh\necho "bwrap: No permissions to create new namespace" >&2\n'
                'exit 1\n')
    os.chmod(path, 0o755)
    return directory


def put_chapter(top, submission, text):
    """Writes text as chapter 5 of the submission directory top/submission."""
    path = os.path.join(top, submission, CHAPTER)
    os.makedirs(os.path.dirname(path))
    with open(path, 'w', encoding='utf-8') as f:
        f.write(text)


def replace_region(text, fragment, code):
    """Replaces the solution lines of <<fragment>> by code."""
    lines = text.split('\n')
    first, last = region(text, fragment)
    lines[first:last + 1] = code.split('\n')
    return '\n'.join(lines)


def line_of(text, needle):
    return text.split('\n').index(needle) + 1


def chunk_span(lines, fragment):
    start = lines.index('<<%s>>=' % fragment)
    end = start + 1
    while lines[end] != '@':
        end += 1
    return start, end


def run_grade(args, cwd=ROOT):
    return subprocess.run([sys.executable, GRADE] + args, cwd=cwd, capture_output=True,
                          text=True)


# What an attack must leave alone in the real repository besides the files
# git tracks: the tests (public and hidden), the grader, and the chapters.
GUARDED = ('tests', 'tools', 'chapters')
# Folders that the real repository's snapshots, and a copy of it, leave out:
# the build's output, git's store, and Python's bytecode (which any test that
# imports a tool writes, at any time).
SKIPPED = ('build', '.git', '__pycache__')


def tree_files(top, skipped=SKIPPED):
    """Every file and link under top, folders named in skipped left out (a
    link to a folder is listed, as a link, and not walked into)."""
    found = []
    for d, dirs, files in os.walk(top):
        links = [x for x in dirs if os.path.islink(os.path.join(d, x))]
        dirs[:] = [x for x in dirs if x not in skipped]
        found += [os.path.join(d, x) for x in files + links]
    return found


def git_files(root, *options):
    """The files (relative to root) that `git ls-files` lists with options, or
    None if root is not the top of a git work tree (an exported tree, or one
    unpacked inside another repository)."""
    try:
        top = subprocess.run(['git', '-C', root, 'rev-parse', '--show-toplevel'],
                             capture_output=True, text=True, check=True).stdout.strip()
        if os.path.realpath(top) != os.path.realpath(root):
            return None
        listed = subprocess.run(['git', '-C', root, 'ls-files', '-z'] + list(options),
                                capture_output=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return None
    return [os.fsdecode(p) for p in listed.split(b'\0') if p]


def book_files(root):
    """The files (relative to root) that a copy of the book takes: those git
    knows, tracked or new and not ignored (a chapter not added yet is graded
    too); outside git, the whole tree but SKIPPED."""
    known = git_files(root, '--cached', '--others', '--exclude-standard')
    if known is None:
        return [os.path.relpath(p, root) for p in tree_files(root)]
    return [p for p in known if os.path.lexists(os.path.join(root, p))]


def copy_book(root, copy):
    """Copies the book at root to copy (links as links, modes kept)."""
    for rel in book_files(root):
        target = os.path.join(copy, rel)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copy2(os.path.join(root, rel), target, follow_symlinks=False)


def watched_files(root):
    """The files of the real repository that an attack which got out of the
    copy it was aimed at could change: those git tracks, and every file under
    GUARDED, new ones included. Left out: untracked files elsewhere (a log of
    this very run at the root, `make test > log.test` or `| tee test.log`, an
    editor's swap file), which whoever runs the tests may write meanwhile and
    nothing grades with, and SKIPPED."""
    files = {os.path.join(root, p) for p in git_files(root, '--cached') or []}
    for folder in GUARDED:
        files.update(tree_files(os.path.join(root, folder)))
    return sorted(files)


def cache_files(cache):
    """The grade cache's files but ccache's store, which is ccache's own: every
    compile rewrites its statistics."""
    return tree_files(cache, skipped=('ccache',))


def digest(path):
    """What a snapshot holds of a file: a link's target, else its bytes' sha256."""
    if os.path.islink(path):
        return 'link to ' + os.readlink(path)
    try:
        with open(path, 'rb') as f:
            return hashlib.sha256(f.read()).hexdigest()
    except OSError:
        return 'unreadable'


def snapshot(files):
    """{file: digest} of the files."""
    return {path: digest(path) for path in files}


def changed(before, after):
    """The files two snapshots disagree on: new, gone or rewritten."""
    return sorted(p for p in set(before) | set(after) if before.get(p) != after.get(p))


def cache_tampering(cache, before, after):
    """What changed in the grade cache that the grader itself never changes.
    The grader writes each entry once, under a name its contents give (a
    judge-* or worker-* folder holding its binary, a needed-* list, a
    verdicts-*.json), and only reads it from then on: a file of `before` that
    changed or went, or a new file in an entry folder `before` had, is someone
    else's doing. New entries at the top, and their locks, are the grader's."""
    entries = {os.path.dirname(p) for p in before} - {cache}
    return [p for p in changed(before, after)
            if p in before or os.path.dirname(p) in entries]


@contextlib.contextmanager
def log_written(path):
    """A file at path that grows while the block runs, as the log of `make
    test > log.test` does; removed afterwards. Yields whether it could be
    written (in a read-only tree no log can be written either)."""
    try:
        log = open(path, 'a')
    except OSError:
        yield False
        return
    stop = threading.Event()

    def write():
        while not stop.wait(0.1):
            log.write('still running\n')
            log.flush()
    writer = threading.Thread(target=write)
    writer.start()
    try:
        yield True
    finally:
        stop.set()
        writer.join()
        log.close()
        os.remove(path)


def make_submissions(ns, root=ROOT):
    """Writes the submissions into ns.subs and sets ns.expected, what each must
    score: {exercise: (status, text in its tests' output)} for chapter 5's
    exercises that do not pass. ns holds tmp, e9, e10, e11 and ch5; the
    attacks aim at `root` (GradeTest gives the scratch copy of the book that
    grades them; a script that grades them with another version of the
    grader, a copy of its own)."""
    ns.subs = os.path.join(ns.tmp, 'submissions')
    ns.out = os.path.join(ns.tmp, 'out')
    ns.cache = os.path.join(ns.tmp, 'cache')
    ns.marker = os.path.join(tempfile.gettempdir(), 'lrt-attack-%d' % os.getpid())
    os.makedirs(ns.subs)
    sol = read(os.path.join(root, CHAPTER))
    ns.solution_text = sol
    student = subprocess.run([sys.executable, os.path.join(root, 'tools', 'exercises', 'markup.py'),
                              'student', CHAPTER], cwd=root, capture_output=True,
                             text=True, check=True).stdout
    both11 = lambda text, code: inject(inject(text, F11[0], code), F11[1], code)  # noqa
    ns.broken = inject(sol, F9, 'this is not C++;')
    crashes = inject(sol, F9, '{ volatile int *p = nullptr; *p = 1; }')
    crashes = inject(crashes, F10, 'std::abort();')
    crashes = both11(crashes, 'throw std::runtime_error("student bug");')
    hangs = inject(sol, F9, 'for (volatile unsigned k = 0;; k = k + 1) {}')
    hangs = inject(hangs, F10, '{ char *big = new char[1ul << 40]; big[0] = 1; '
                   'delete[] big; }')
    hangs = both11(hangs, 'std::exit(0);')
    fake = inject(sol, F10, 'std::printf("[       OK ] Ex5_10.All\\n'
                  '[  PASSED  ] 1 test.\\n");\nstd::exit(0);')
    # The reciprocal and its sign swapped: every check of ex-5.10 fails.
    wrong = replace_region(sol, F10, 'Float invD = -invDir[i];\nint isNeg = !dirIsNeg[i];')
    # Two exercises of three done: ex-5.10 left as the stub.
    two_of_three = replace_region(
        sol, F10, '\n'.join(student.split('\n')[region(student, F10)[0]:
                                                region(student, F10)[1] + 1]))
    lines = sol.split('\n')
    renamed = sol.replace('<<%s>>' % F10, '<<My own lookup>>')
    s, e = chunk_span(lines, F10)
    deleted = '\n'.join(lines[:s] + lines[e + 1:])
    s, e = chunk_span(lines, F11[0])
    duplicated = '\n'.join(lines[:e + 1] + [''] + lines[s:e + 1] + lines[e + 1:])
    ns.duplicate_line = e + 3
    # Outside the exercises: the slab test made to accept everything
    # (restored by default).
    reject = 'if (t0 > t1) return false;'
    assert reject in sol, 'the edit outside the exercises no longer applies'
    changed = sol.replace(reject, 'if (t0 > t1 && false) return false;')
    ns.renamed_line = line_of(renamed, '<<My own lookup>>=')
    ns.broken_line = line_of(ns.broken, 'this is not C++;')

    def put(name, text, where=CHAPTER):
        path = os.path.join(ns.subs, name, where)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, 'w', encoding='utf-8') as f:
            f.write(text)

    # The solutions, as a zip with the chapter in a folder of its own.
    with zipfile.ZipFile(os.path.join(ns.subs, 'solution.zip'), 'w') as z:
        z.writestr('lrt/chapters/05-slab-test.md', sol)
        z.writestr('lrt/README.txt', 'my work')
    put('student', student, '05-slab-test.md')        # no chapters/ folder
    put('two_of_three', two_of_three)
    # A group submission: the instructor's roster names its students (the
    # gradebook gives each a row). The metadata file inside it, which a
    # student could write, names someone else and is ignored.
    put('group', two_of_three)
    ns.group = [{'name': 'Ada Lovelace', 'email': 'ada@example.edu', 'id': 11},
                {'name': 'Alan Turing', 'email': 'alan@example.edu', 'id': 12}]
    ns.roster = os.path.join(ns.tmp, 'roster.csv')
    with open(ns.roster, 'w') as f:
        f.write('submission,student,login\n' + ''.join(
            'group,%s,%s\n' % (u['name'], u['email']) for u in ns.group))
    with open(os.path.join(ns.subs, 'group', 'submission_metadata.json'), 'w') as f:
        json.dump({'id': 1, 'users': [{'name': 'Victim', 'email': 'victim@example.edu',
                                       'id': 13}]}, f)
    put('compile_error', ns.broken)
    put('crashes', crashes)
    put('hangs', hangs)
    put('fake_pass', fake)
    put('wrong_answer', wrong)
    put('renamed', renamed)
    put('deleted', deleted)
    put('duplicated', duplicated)
    put('changed_outside', changed)
    # A compile error in a chapter that is spliced (code changed outside
    # the exercises): the error still names the student's line.
    spliced = inject(changed, F11[0], 'this is not C++ either;')
    ns.spliced_line = line_of(spliced, 'this is not C++ either;')
    put('compile_error_spliced', spliced)
    os.makedirs(os.path.join(ns.subs, 'empty'))
    # Files that try to replace tests, plus unsafe members.
    with tarfile.open(os.path.join(ns.subs, 'tamper.tar.gz'), 'w:gz') as t:
        def add(name, data, kind=tarfile.REGTYPE, link=''):
            info = tarfile.TarInfo(name)
            info.type, info.linkname = kind, link
            info.size = len(data) if kind == tarfile.REGTYPE else 0
            t.addfile(info, io.BytesIO(data) if kind == tarfile.REGTYPE else None)
        add('chapters/05-slab-test.md', sol.encode())
        add('tests/ch05/test_x.cpp', b'#include <gtest/gtest.h>\nTEST(Ex5_9_X, Y) {}\n')
        add('tests/hidden/ch05/test_ex5_hidden.cpp', b'// nothing to see\n')
        add('../01-introduction.md', b'# escaped\n')
        add('../../../../../../tmp/lrt-escaped.md', b'# escaped\n')
        add('chapters/01-introduction.md', b'', tarfile.SYMTYPE, '/etc/passwd')
    # The attacks, each in ex-5.10's region.
    ns.attacks = sorted(attacks.ATTACKS) + sorted(attacks.EVERY_CALL) + ['answers_by_name']
    for name in ns.attacks:
        code = attacks.attack_code(name, repo=root, out=os.path.join(ns.out, name),
                                   marker=ns.marker + '-' + name, cache=ns.cache)
        put(name, replace_region(sol, F10, code))
    put('compile_leak', replace_region(sol, F10, attacks.compile_leak(root)))

    # What each submission must score: {exercise: (status, text in its
    # tests' output)} for chapter 5's exercises that do not pass. The text
    # may be a pair: (public tests' text, hidden tests' text). A hidden test
    # shows nothing the code chose (what it threw, a signal, an exit status:
    # its worker saw the hidden inputs), only the kind of failure; but the
    # message of the exercise's own stub.
    def every(status, text=None):
        return {e: (status, text % e if text and '%s' in text else text)
                for e in ns.ch5}
    stub10 = {ns.e10: ('FAIL', 'Exercise %s is not done yet' % ns.e10)}
    threw = 'the code threw an exception (not shown for a hidden test)'
    attacked = {ns.e10: ('FAIL', ('attack only: no solution here', threw))}
    ns.expected = {
        'solution': {}, 'duplicated': {}, 'changed_outside': {}, 'tamper': {},
        'student': every('FAIL', 'Exercise %s is not done yet'),
        'two_of_three': stub10, 'group': stub10,
        'compile_error': {ns.e9: ('COMPILE-ERROR', None)},
        'compile_error_spliced': {ns.e11: ('COMPILE-ERROR', None)},
        'empty': every('NOT-RUN', 'is not in the submission'),
        'crashes': {ns.e9: ('CRASH', ('SIGSEGV', ': the code crashed\n')),
                    ns.e10: ('CRASH', ('SIGABRT', ': the code crashed\n')),
                    ns.e11: ('FAIL', ('student bug', threw))},
        'hangs': {ns.e9: ('TIMEOUT', None),
                  ns.e10: ('OOM', ('bad_alloc', ': the code ran out of memory\n')),
                  ns.e11: ('CRASH', ('exited with status 0', ': the code crashed\n'))},
        'fake_pass': {ns.e10: ('CRASH', ('exited with status 0', ': the code crashed\n'))},
        'wrong_answer': {ns.e10: ('FAIL', None)},
        'renamed': stub10,
        'deleted': stub10,
        'compile_leak': {ns.e10: ('COMPILE-ERROR', 'is not compiled: ')},
    }
    for name in ns.attacks:
        ns.expected[name] = attacked
    ns.expected['huge_allocation'] = {ns.e10: ('OOM', ('bad_alloc',
                                                       ': the code ran out of memory\n'))}
    # On a busy machine the forks can outlast a call's time limit: TIMEOUT
    # instead of FAIL, and the exercise scores 0 either way.
    ns.expected['fork_bomb'] = {ns.e10: (('FAIL', 'TIMEOUT'),
                                         ('attack only: no solution here', threw))}


class GradeTest(unittest.TestCase):
    # Where the batch is graded: with bubblewrap here, without namespaces in
    # GradeWithoutNamespacesTest; and how the feedback names the isolation.
    FALLBACK = False
    ISOLATION = 'bubblewrap sandbox'

    @classmethod
    def setUpClass(cls):
        # What the book says is to be graded, and what each test must find.
        cls.book = book_exercises()
        cls.points = {e: x['points'] for e, x in cls.book.items()}
        cls.chapters = sorted({x['chapter'] for x in cls.book.values()})
        cls.tests = exercise_tests(cls.chapters)
        cls.total = sum(cls.points.values())
        owner = {f: e for e, x in cls.book.items() for f in x['fragments']}
        cls.e9, cls.e10, cls.e11 = owner.get(F9), owner.get(F10), owner.get(F11[0])
        cls.ch5 = sorted(e for e, x in cls.book.items() if x['chapter'] == '05')
        cls.ch5_points = sum(cls.points[e] for e in cls.ch5)
        cls.hidden_words = hidden_only_identifiers(cls.chapters)

        cls.tmp = tempfile.mkdtemp(prefix='lrt-grade-test-')
        # The batch is graded by a scratch copy of the repository, which the
        # attacks aim at: every file of it can be watched, while whoever runs
        # the tests writes what they like into the real one.
        cls.copy = os.path.join(cls.tmp, 'repo')
        copy_book(ROOT, cls.copy)
        make_submissions(cls, root=cls.copy)
        # Every chapter with exercises is graded, named explicitly so that a
        # kit's exercises.json (the default's source in a kit) changes nothing.
        cls.graded = ['--chapters', ' '.join(cls.chapters)]
        grade = [sys.executable, os.path.join(cls.copy, 'tools', 'grading', 'grade.py'),
                 '--cache', cls.cache, '--time-limit', str(TIME_LIMIT),
                 '--memory-limit', '512'] + cls.graded
        # Nor does the copy's grader write its bytecode into the copy.
        env = dict(os.environ, PYTHONDONTWRITEBYTECODE='1')
        if cls.FALLBACK:
            env['PATH'] = (failing_bwrap(os.path.join(cls.tmp, 'no-bwrap')) + os.pathsep +
                           env['PATH'])
        # A clean grading first, so that the cache holds what the attacks aim
        # at there (a judge, a worker, verdicts) before they run.
        proc = subprocess.run(grade + [os.path.join(cls.subs, 'solution.zip'), '--out',
                                       os.path.join(cls.tmp, 'clean'), '--quiet'],
                              cwd=cls.copy, env=env, capture_output=True, text=True)
        cls.clean_output = proc.stdout + proc.stderr
        cls.clean_status = proc.returncode
        # A log grows at the root of the real repository meanwhile, as `make
        # test > log.test` writes one: it is no attack's doing.
        with log_written(os.path.join(ROOT, '.lrt-test-log-%d' % os.getpid())):
            cls.before, cls.cache_before = cls.watch()
            proc = subprocess.run(grade + ['--batch', cls.subs, '--out', cls.out,
                                           '--roster', cls.roster],
                                  cwd=cls.copy, env=env, capture_output=True, text=True)
            cls.batch_output = proc.stdout + proc.stderr
            cls.batch_status = proc.returncode
            cls.results_after_batch = snapshot(tree_files(cls.out, skipped=()))
            # Long enough for an escaped process to do what it waited to do.
            time.sleep(6)
            cls.after, cls.cache_after = cls.watch()
            cls.results_later = snapshot(tree_files(cls.out, skipped=()))

    @classmethod
    def watch(cls):
        """Snapshots of what the attacks must not change: every file of the
        copy, of the submissions, and the real repository's watched files;
        and, apart, the cache's."""
        files = (tree_files(cls.copy, skipped=()) + tree_files(cls.subs, skipped=()) +
                 watched_files(ROOT))
        return snapshot(files), snapshot(cache_files(cls.cache))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)
        for name in getattr(cls, 'attacks', []):
            if os.path.exists(cls.marker + '-' + name):
                os.remove(cls.marker + '-' + name)

    def results(self, name, out=None):
        with open(os.path.join(out or self.out, name, 'results.json'), encoding='utf-8') as f:
            return json.load(f)

    def share(self, exercise):
        return round(self.points[exercise] / len(self.tests[exercise]), 4)

    def expected_score(self, expected):
        return sum(self.points[e] for e in self.ch5 if e not in expected)

    def assertExercise(self, data, exercise, status, contains=None):
        tests = [t for t in data['tests'] if t['name'].startswith(exercise + ' ')]
        self.assertEqual(sorted(t['name'] for t in tests),
                         sorted('%s %s' % (exercise, name) for name, _ in self.tests[exercise]))
        hidden = {name for name, h in self.tests[exercise] if h}
        # status may be a tuple of the statuses allowed; contains applies to
        # the first of them. contains may be a pair: (the public tests' text,
        # the hidden tests'), and then a hidden test must not show the first.
        allowed = status if isinstance(status, tuple) else (status,)
        shown, kept = contains if isinstance(contains, tuple) else (contains, contains)
        for t in tests:
            self.assertEqual(len(t['tags']), 1, t)
            self.assertIn(t['tags'][0], allowed, t)
            got = t['tags'][0]
            self.assertEqual(t['status'], 'passed' if got == 'PASS' else 'failed')
            self.assertAlmostEqual(t['max_score'], self.share(exercise), places=4)
            self.assertAlmostEqual(t['score'], self.share(exercise) if got == 'PASS' else 0,
                                   places=4)
            self.assertEqual(t['visibility'], 'after_published'
                             if t['name'].split()[1] in hidden else 'visible', t)
            self.assertIn('**%s**' % got, t['output'])
            if contains and got == allowed[0]:
                if t['name'].split()[1] not in hidden:
                    self.assertIn(shown, t['output'], t)
                else:
                    self.assertIn(kept, t['output'], t)
                    if kept != shown:
                        self.assertNotIn(shown, t['output'], t)

    def assertGraded(self, data, expected, max_score=None):
        """Chapter 5's exercises as expected (the rest pass), the other
        chapters' exercises NOT-RUN, every test of the graded chapters listed
        once, and the points added up."""
        self.assertEqual(sorted(t['name'] for t in data['tests']),
                         sorted('%s %s' % (e, name) for e in self.tests
                                for name, _ in self.tests[e]))
        for e in self.ch5:
            self.assertExercise(data, e, *expected.get(e, ('PASS', None)))
        for e in self.tests:
            if e not in self.ch5:
                self.assertExercise(data, e, 'NOT-RUN', 'is not in the submission')
        score = self.expected_score(expected)
        self.assertAlmostEqual(data['score'], score, places=3)
        self.assertAlmostEqual(sum(t['score'] for t in data['tests']), score, places=2)
        self.assertEqual(data['max_score'], self.total if max_score is None else max_score)
        got = {x['exercise']: (x['points'], x['max_points'])
               for x in data['extra_data']['exercises']}
        self.assertEqual(set(got), set(self.tests))
        for e, (points, max_points) in got.items():
            self.assertEqual(max_points, self.points[e])
            self.assertAlmostEqual(points, self.points[e] if e in self.ch5 and
                                   e not in expected else 0, places=3)

    def assertSubmission(self, name):
        data = self.results(name)
        self.assertGraded(data, self.expected[name])
        return data

    def test_expectations_match_the_book(self):
        # The oracle itself: the listing's points are the divs', its tests are
        # those the test sources hold, and chapter 5's exercises are the
        # three whose fragments the submissions edit.
        self.assertEqual(self.points, div_points())
        self.assertEqual(set(self.tests), set(self.book))
        for e, x in self.book.items():
            self.assertEqual(sorted(n for n, h in self.tests[e] if not h),
                             sorted(x['public_tests']), e)
            self.assertEqual(sorted(n for n, h in self.tests[e] if h),
                             sorted(x['hidden_tests']), e)
            self.assertTrue(x['public_tests'] and x['hidden_tests'], e)
        edited = {self.e9, self.e10, self.e11}
        self.assertEqual(len(edited), 3)
        self.assertEqual(edited, set(self.ch5))
        self.assertTrue(self.hidden_words)
        self.assertEqual(self.batch_status, 0, self.batch_output)

    def test_solution_full_marks(self):
        data = self.assertSubmission('solution')
        self.assertAlmostEqual(data['score'], self.ch5_points, places=3)
        self.assertEqual(data['stdout_visibility'], 'hidden')
        hidden = {'%s %s' % (e, n) for e in self.tests for n, h in self.tests[e] if h}
        self.assertEqual({t['name'] for t in data['tests']
                          if t['visibility'] == 'after_published'}, hidden)
        self.assertIn('ignored `lrt/README.txt`', data['output'])
        self.assertIn(self.ISOLATION, data['output'])
        junit = read(os.path.join(self.out, 'solution', 'junit.xml'))
        count = sum(len(tests) for tests in self.tests.values())
        self.assertEqual(junit.count('<testcase '), count)
        self.assertNotIn('<failure', junit)
        self.assertEqual(junit.count('<skipped '), count - sum(
            len(self.tests[e]) for e in self.ch5))
        table = read(os.path.join(self.out, 'solution', 'results.txt'))
        self.assertIn('total %.2f / %d' % (self.ch5_points, self.total), table)

    def test_student_edition_zero(self):
        data = self.assertSubmission('student')
        self.assertEqual(data['score'], 0)
        # Each exercise fails on its own stub, not on another's.
        for e in self.ch5:
            for t in data['tests']:
                if t['name'].startswith(e + ' '):
                    self.assertEqual(re.findall(r'Exercise (ex-[\d.]+) is not done', t['output']),
                                     [e], t)

    def test_two_of_three_exercises_score_those_two(self):
        data = self.assertSubmission('two_of_three')
        self.assertAlmostEqual(data['score'], self.ch5_points - self.points[self.e10], places=3)

    def test_compile_error_costs_its_exercise_only(self):
        data = self.assertSubmission('compile_error')
        self.assertIn('chapters/05-slab-test.md:%d' % self.broken_line, data['output'])
        self.assertIn('Compile error in %s' % self.e9, data['output'])

    def test_compile_error_after_splice(self):
        data = self.assertSubmission('compile_error_spliced')
        self.assertIn('chapters/05-slab-test.md:%d' % self.spliced_line, data['output'])
        self.assertIn('**Warning**: code outside the exercises was changed', data['output'])

    def test_crash_abort_exception(self):
        self.assertSubmission('crashes')

    def test_timeout_oom_exit(self):
        self.assertSubmission('hangs')

    def test_fake_gtest_output_counts_for_nothing(self):
        data = self.assertSubmission('fake_pass')
        self.assertAlmostEqual(data['score'], self.ch5_points - self.points[self.e10],
                               places=3)

    def test_wrong_answer_shows_public_failures_and_hides_hidden_ones(self):
        data = self.assertSubmission('wrong_answer')
        public = [t for t in data['tests'] if t['name'].startswith(self.e10 + ' ') and
                  t['visibility'] == 'visible']
        hidden = [t for t in data['tests'] if t['name'].startswith(self.e10 + ' ') and
                  t['visibility'] == 'after_published']
        self.assertTrue(public and hidden)
        for t in public:     # the check that failed, where it is
            self.assertRegex(t['output'], r'tests/ch05/\w+\.cpp:\d+')
        hint = 'Hint: ' + self.hint(self.e10)
        for t in hidden:     # that it failed, and the hint; nothing of the test
            self.assertEqual(t['output'], HIDDEN_FAIL + '\n\n' + hint)
        for where in ('junit.xml', 'results.txt'):
            text = read(os.path.join(self.out, 'wrong_answer', where))
            self.assertNotIn('hidden/ch05', text)
            self.assertIn('its checks are not shown', text)

    def hint(self, exercise):
        lines = self.solution_text.split('\n')
        start = [n for n, l in enumerate(lines) if '#%s ' % exercise in l][0]
        begin = lines.index('::: hint', start)
        end = lines.index(':::', begin)
        return ' '.join(l.strip() for l in lines[begin + 1:end] if l.strip())

    def test_no_grade_shows_hidden_test_code(self):
        for name in self.expected:
            for where in ('results.json', 'junit.xml', 'results.txt'):
                text = read(os.path.join(self.out, name, where))
                for word in self.hidden_words:
                    self.assertNotRegex(text, r'\b%s\b' % word, '%s/%s' % (name, where))

    def test_renamed_chunk(self):
        data = self.assertSubmission('renamed')
        self.assertIn('chapters/05-slab-test.md:%d: exercise chunk <<%s>> (%s) was '
                      'renamed to <<My own lookup>>' % (self.renamed_line, F10, self.e10),
                      data['output'])

    def test_deleted_chunk(self):
        data = self.assertSubmission('deleted')
        self.assertIn('exercise chunk <<%s>> (%s) was deleted' % (F10, self.e10),
                      data['output'])

    def test_duplicated_chunk(self):
        data = self.assertSubmission('duplicated')
        self.assertIn('chapters/05-slab-test.md:%d: exercise chunk <<%s>> (%s) is '
                      'defined 2 times' % (self.duplicate_line, F11[0], self.e11),
                      data['output'])

    def test_change_outside_exercises_restored(self):
        data = self.assertSubmission('changed_outside')
        self.assertIn('**Warning**: code outside the exercises was changed', data['output'])
        self.assertIn('differs from the book', data['output'])

    def test_tampering_files_ignored(self):
        data = self.assertSubmission('tamper')
        for name in ('tests/ch05/test_x.cpp', 'tests/hidden/ch05/test_ex5_hidden.cpp'):
            self.assertIn('ignored `%s`: not a chapter file' % name, data['output'])
        self.assertIn('ignored `../01-introduction.md`: unsafe path', data['output'])
        self.assertIn('ignored `chapters/01-introduction.md`: not a regular file',
                      data['output'])
        self.assertFalse(os.path.exists('/tmp/lrt-escaped.md'))
        names = [t['name'] for t in data['tests']]
        self.assertNotIn('Ex5_9_X.Y', ' '.join(names))

    def test_empty_submission(self):
        data = self.assertSubmission('empty')
        self.assertIn('No chapter file found', data['output'])

    # -- Attacks --------------------------------------------------------------

    def test_attacks_gain_nothing(self):
        for name in self.attacks + ['compile_leak']:
            with self.subTest(attack=name):
                data = self.assertSubmission(name)
                self.assertAlmostEqual(data['score'], self.ch5_points -
                                       self.points[self.e10], places=3)

    def test_attacks_change_no_file_outside_the_results(self):
        # The copy, the submissions, the real repository's watched files and
        # the cache's entries, before the batch and seconds after it ended; no
        # marker outside; the results unchanged since the grader wrote them.
        self.assertEqual(changed(self.before, self.after), [])
        self.assertEqual(cache_tampering(self.cache, self.cache_before, self.cache_after), [])
        for name in self.attacks:
            self.assertFalse(os.path.exists(self.marker + '-' + name), name)
        self.assertEqual(self.results_after_batch, self.results_later)

    def test_cache_held_what_the_attacks_aim_at(self):
        # The cache's check above means something only if the clean grading
        # left there what an attack would rewrite: a judge, a worker, verdicts.
        self.assertEqual(self.clean_status, 0, self.clean_output)
        names = [os.path.relpath(p, self.cache) for p in self.cache_before]
        for entry in (r'judge-05-\w+/judge', r'worker-05-\w+/worker', r'verdicts-\w+\.json'):
            self.assertTrue([n for n in names if re.fullmatch(entry, n)], (entry, names))

    def test_attack_names_no_grader_process(self):
        # A killed grader would have left no results: every submission has
        # them, and the batch says no grader failed.
        self.assertIn('(0 with grader errors)', self.batch_output)

    # -- Batch ----------------------------------------------------------------

    def test_batch_csv(self):
        with open(os.path.join(self.out, 'grades.csv')) as f:
            rows = list(csv.DictReader(f))
        totals, seen = {}, {}
        for row in rows:
            totals[row['student']] = totals.get(row['student'], 0) + float(row['points'])
            seen.setdefault(row['student'], []).append(row['exercise'])
            self.assertEqual(int(row['max_points']), self.points[row['exercise']], row)
            self.assertEqual(row['chapter'], self.book[row['exercise']]['chapter'], row)
        expected = {name: self.expected_score(e) for name, e in self.expected.items()}
        self.assertEqual({k: round(v, 3) for k, v in totals.items()}, expected)
        for student, exercises in seen.items():
            self.assertEqual(sorted(exercises), sorted(self.points), student)
        self.assertIn('graded %d submissions' % len(expected), self.batch_output)

    def test_gradebook_has_a_row_per_student(self):
        with open(os.path.join(self.out, 'gradebook.csv'), newline='') as f:
            rows = list(csv.reader(f))
        order = [e for e in self.book if e in self.points]   # the book's order
        self.assertEqual(rows[0], ['Student', 'SIS Login ID', 'Section'] + order + ['Total'])
        self.assertEqual({r[2] for r in rows[1:]}, {''})
        got = {(r[0], r[1]): r[3:] for r in rows[1:]}
        self.assertEqual(len(got), len(rows) - 1)
        people = {(n, n): n for n in self.expected if n != 'group'}
        people.update({(u['name'], u['email']): 'group' for u in self.group})
        self.assertEqual(sorted(got), sorted(people))
        for who, name in people.items():
            expected = self.expected[name]
            values = [self.points[e] if e in self.ch5 and e not in expected else 0
                      for e in order]
            self.assertEqual([float(v) for v in got[who][:-1]], values, who)
            self.assertAlmostEqual(float(got[who][-1]), self.expected_score(expected),
                                   places=3)

    def test_metadata_inside_a_submission_is_ignored(self):
        with open(os.path.join(self.out, 'gradebook.csv'), newline='') as f:
            logins = [r[1] for r in csv.reader(f)]
        self.assertNotIn('victim@example.edu', logins)
        self.assertIn('group: its submission_metadata.json was ignored', self.batch_output)

    # -- Grading by a course plan (docs/course.md) ---------------------------

    def plan(self, text):
        path = os.path.join(tempfile.mkdtemp(dir=self.tmp), 'course.toml')
        with open(path, 'w') as f:
            f.write(text)
        return path

    def test_plan_grades_its_assignment_with_its_points(self):
        plan = self.plan('[[assignment]]\nname = "first"\nexercises = ["%s"]\n\n'
                         '[[assignment]]\nname = "second"\nexercises = ["%s", "%s"]\n'
                         'points = { "%s" = 7.5 }\n' % (self.e10, self.e9, self.e11, self.e9))
        maximum = 7.5 + self.points[self.e11]
        for name in ('solution.zip', 'two_of_three'):   # ex-5.10 is not in "second"
            data = self.grade_one(name, ['--plan', plan, '--assignment', 'second'])
            self.assertEqual(data['max_score'], maximum)
            self.assertAlmostEqual(data['score'], maximum, places=3)
            self.assertEqual(sorted(t['name'] for t in data['tests']),
                             sorted('%s %s' % (e, n) for e in (self.e9, self.e11)
                                    for n, _ in self.tests[e]))
            for t in data['tests']:
                if t['name'].startswith(self.e9 + ' '):
                    self.assertAlmostEqual(t['max_score'], 7.5 / len(self.tests[self.e9]),
                                           places=4)
        data = self.grade_one('two_of_three', ['--plan', plan, '--assignment', 'first'])
        self.assertEqual(data['score'], 0)
        self.assertEqual(data['max_score'], self.points[self.e10])

    def test_bad_plan_is_named_with_its_line(self):
        base = '[[assignment]]\nname = "a"\nexercises = ["%s"]\n' % self.e9
        cases = [(base + 'colour = "red"\n', ':4: ', "unknown key 'colour'"),
                 (base.replace(self.e9, 'ex-99.1'), ':3: ', 'ex-99.1 is not an exercise'),
                 (base + '[[assignment]]\nname = "b"\nexercises = ["%s"]\n' % self.e9,
                  ':6: ', 'already in'),
                 (base + 'release = 2027-09-02\ndue = 2027-09-01\n', ':5: ',
                  'is before release'),
                 (base + 'points = { "%s" = -1 }\n' % self.e9, ':4: ', 'positive number'),
                 (base + 'name = [\n', ':4:', 'not valid TOML')]
        for text, line, message in cases:
            plan = self.plan(text)
            proc = run_grade([os.path.join(self.subs, 'empty'), '--out',
                              os.path.join(self.tmp, 'rejected'), '--plan', plan,
                              '--assignment', 'a', '--quiet'])
            self.assertNotEqual(proc.returncode, 0, text)
            self.assertIn(plan + line, proc.stderr)
            self.assertIn(message, proc.stderr)
            self.assertFalse(os.path.exists(os.path.join(self.tmp, 'rejected')))
        proc = run_grade([os.path.join(self.subs, 'empty'), '--plan', self.plan(base),
                          '--assignment', 'nope', '--quiet'])
        self.assertIn("no assignment named 'nope' (assignments: a)", proc.stderr)

    # -- Which chapters are graded ------------------------------------------

    def grade_one(self, name, args, root=None):
        out = tempfile.mkdtemp(dir=self.tmp)
        proc = run_grade([os.path.join(self.subs, name), '--out', out, '--cache', self.cache,
                          '--time-limit', str(TIME_LIMIT), '--quiet'] + args +
                         (['--root', root] if root else []))
        self.assertEqual(proc.returncode, 0, proc.stderr)
        return json.loads(read(os.path.join(out, 'results.json')))

    def assertOnly(self, data, chapters):
        """data grades exactly the exercises of chapters (nothing else listed)."""
        exercises = sorted(e for e in self.tests if self.book[e]['chapter'] in chapters)
        self.assertEqual(sorted(t['name'] for t in data['tests']),
                         sorted('%s %s' % (e, n) for e in exercises for n, _ in self.tests[e]))
        self.assertEqual(data['max_score'], sum(self.points[e] for e in exercises))
        self.assertEqual(sorted(x['exercise'] for x in data['extra_data']['exercises']),
                         exercises)

    def test_chapters_option_grades_only_those(self):
        data = self.grade_one('solution.zip', ['--chapters', '5'])
        self.assertOnly(data, ['05'])
        self.assertAlmostEqual(data['score'], self.ch5_points, places=3)
        for e in self.ch5:
            self.assertExercise(data, e, 'PASS')

    def test_chapter_outside_the_assignment_is_left_alone(self):
        others = [c for c in self.chapters if c != '05']
        if not others:
            self.skipTest('no chapter but 5 has exercises')
        data = self.grade_one('solution.zip', ['--chapters', others[0]])
        self.assertOnly(data, [others[0]])
        self.assertEqual(data['score'], 0)
        self.assertIn('`lrt/chapters/05-slab-test.md`: not graded in this assignment',
                      data['output'])
        self.assertTrue(all(t['tags'] == ['NOT-RUN'] for t in data['tests']))

    def test_chapters_option_rejects_what_it_cannot_grade(self):
        cases = [('99', 'there is no chapter 99'), ('two', 'names chapters by number')]
        numbers = [os.path.basename(p)[:2] for p in chapter_files()]
        cases += [(n, 'chapter %s has no exercises' % n) for n in numbers
                  if n not in self.chapters][:1]
        for chapters, message in cases:
            proc = run_grade([os.path.join(self.subs, 'empty'), '--out',
                              os.path.join(self.tmp, 'rejected'), '--chapters', chapters,
                              '--quiet'])
            self.assertNotEqual(proc.returncode, 0, chapters)
            self.assertIn(message, proc.stderr)
            self.assertFalse(os.path.exists(os.path.join(self.tmp, 'rejected')))

    def kit(self, chosen):
        """A book that is a kit built for the chapters chosen: this book's
        chapters, tests and tools, and an exercises.json."""
        root = tempfile.mkdtemp(dir=self.tmp)
        for name in ('chapters', 'tests', 'tools'):
            os.symlink(os.path.join(ROOT, name), os.path.join(root, name))
        with open(os.path.join(root, 'exercises.json'), 'w') as f:
            json.dump({'edition': 'solution', 'chosen_chapters': chosen}, f)
        return root

    def test_kit_grades_the_chapters_it_was_built_for(self):
        # A kit for chapters 1 to 5: chapter 1 has no exercises.
        data = self.grade_one('empty', [], root=self.kit(['01', '05']))
        self.assertOnly(data, ['05'])
        others = [c for c in self.chapters if c != '05']
        if others:
            data = self.grade_one('empty', [], root=self.kit(others[-1:]))
            self.assertOnly(data, others[-1:])
            # --chapters wins over the kit's choice.
            data = self.grade_one('empty', ['--chapters', '05'], root=self.kit(others[-1:]))
            self.assertOnly(data, ['05'])

    def test_default_grades_every_chapter_with_exercises(self):
        data = self.grade_one('empty', [])
        manifest = os.path.join(ROOT, 'exercises.json')
        if os.path.exists(manifest):   # this book is a kit
            chosen = json.loads(read(manifest))['chosen_chapters']
            self.assertOnly(data, [c for c in self.chapters if c in chosen])
        else:
            self.assertOnly(data, self.chapters)

    # -- --allow-changes-outside-exercises ----------------------------------

    def grade_allowing_changes(self, name):
        return self.grade_one(name, self.graded + ['--allow-changes-outside-exercises'])

    def test_allow_changes_keeps_a_consistent_rename(self):
        # Definition and use renamed together: the student's code works, and
        # with the flag it is graded as written (the same code as the book's).
        data = self.grade_allowing_changes('renamed')
        self.assertGraded(data, {})
        self.assertIn('allowed; graded with your code', data['output'])
        self.assertIn('was renamed to <<My own lookup>>', data['output'])

    def test_allow_changes_grades_the_students_code(self):
        # With the flag, a deleted exercise chunk is the student's text as
        # written: the tangle fails, and every exercise scores 0.
        data = self.grade_allowing_changes('deleted')
        self.assertGraded(data, {e: ('COMPILE-ERROR', None) for e in self.ch5})
        self.assertIn('allowed; graded with your code', data['output'])


def append(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'a') as f:
        f.write(text)


@unittest.skipUnless(os.geteuid() == 0, 'the fallback without namespaces needs root')
class GradeWithoutNamespacesTest(GradeTest):
    """The same batch, graded where bubblewrap cannot make namespaces (a
    `bwrap` on PATH that fails as it does in a container that forbids them):
    every submission must score as it does in the sandbox, and no attack may
    gain a point, change a file or show a hidden test."""
    FALLBACK = True
    ISOLATION = 'as an unprivileged user, without namespaces'


# The tests that grade with options of their own (plans, --chapters, kits,
# --allow-changes-outside-exercises, the snapshot helpers) do not depend on
# the isolation: they run once, in GradeTest.
GRADED_IN_THE_BATCH = {
    'test_expectations_match_the_book', 'test_solution_full_marks',
    'test_student_edition_zero', 'test_two_of_three_exercises_score_those_two',
    'test_compile_error_costs_its_exercise_only', 'test_compile_error_after_splice',
    'test_crash_abort_exception', 'test_timeout_oom_exit',
    'test_fake_gtest_output_counts_for_nothing',
    'test_wrong_answer_shows_public_failures_and_hides_hidden_ones',
    'test_no_grade_shows_hidden_test_code', 'test_renamed_chunk', 'test_deleted_chunk',
    'test_duplicated_chunk', 'test_change_outside_exercises_restored',
    'test_tampering_files_ignored', 'test_empty_submission', 'test_attacks_gain_nothing',
    'test_attacks_change_no_file_outside_the_results', 'test_cache_held_what_the_attacks_aim_at',
    'test_attack_names_no_grader_process', 'test_batch_csv',
    'test_gradebook_has_a_row_per_student', 'test_metadata_inside_a_submission_is_ignored'}
for _name in [n for n in dir(GradeTest) if n.startswith('test')]:
    if _name not in GRADED_IN_THE_BATCH:
        setattr(GradeWithoutNamespacesTest, _name, None)


class WatchTest(unittest.TestCase):
    """The snapshots of GradeTest, on a small repository and cache: they see
    what an attack could write, and not what the person running the tests or
    the grader writes."""

    def setUp(self):
        tmp = tempfile.mkdtemp(prefix='lrt-watch-test-')
        self.addCleanup(shutil.rmtree, tmp)
        self.repo, self.cache = os.path.join(tmp, 'repo'), os.path.join(tmp, 'cache')
        for rel in ('Makefile', 'tests/ch05/test_a.cpp',
                    'tests/hidden/ch05/test_b.cpp', 'tools/grading/grade.py', 'chapters/05-a.md'):
            append(os.path.join(self.repo, rel), rel + '\n')
        append(os.path.join(self.repo, '.gitignore'), '/build/\n__pycache__/\n')
        subprocess.run(['git', 'init', '-q', self.repo], check=True)
        subprocess.run(['git', '-C', self.repo, 'add', '.'], check=True)
        # Untracked: a log that was there already, and files git ignores.
        for rel in ('log.test', 'build/lrt.o', 'tools/__pycache__/grade.pyc'):
            append(os.path.join(self.repo, rel), 'before\n')
        # A cache that a clean grading filled; its locks are empty.
        for rel in ('judge-05-k1/judge', 'worker-05-k2/worker', 'needed-05-k3',
                    'verdicts-k4.json', 'ccache/stats'):
            append(os.path.join(self.cache, rel), rel + '\n')
        append(os.path.join(self.cache, 'judge-05-k1.lock'), '')

    def watch(self):
        return snapshot(watched_files(self.repo)), snapshot(cache_files(self.cache))

    def write(self, top, paths):
        """Appends a line to each of paths (relative to top), made if new;
        their full paths, sorted."""
        for rel in paths:
            append(os.path.join(top, rel), 'written\n')
        return sorted(os.path.join(top, rel) for rel in paths)

    def test_writes_an_attack_could_make_are_caught(self):
        before, cache_before = self.watch()
        planted = self.write(self.repo, [
            'tests/ch05/test_a.cpp', 'tests/ch05/test_zz_attack.cpp',
            'tools/grading/grade.py', 'tools/planted.py',
            'chapters/05-a.md', 'chapters/06-planted.md', 'Makefile'])
        gone = os.path.join(self.repo, 'tests/hidden/ch05/test_b.cpp')
        os.remove(gone)
        in_cache = self.write(self.cache, [
            'judge-05-k1/judge', 'judge-05-k1/worker', 'worker-05-k2/worker',
            'needed-05-k3', 'verdicts-k4.json'])
        after, cache_after = self.watch()
        self.assertEqual(changed(before, after), sorted(planted + [gone]))
        self.assertEqual(cache_tampering(self.cache, cache_before, cache_after), in_cache)

    def test_a_log_written_meanwhile_is_not_reported(self):
        before, _ = self.watch()
        self.write(self.repo, ['log.test', 'test.log', '.Makefile.swp', 'build/lrt.o',
                               'tools/__pycache__/grade.pyc'])
        after, _ = self.watch()
        self.assertEqual(changed(before, after), [])

    def test_the_graders_own_cache_writes_are_not_reported(self):
        _, before = self.watch()
        self.write(self.cache, ['worker-05-k5/worker', 'verdicts-k6.json', 'ccache/stats',
                                'ccache/a/b.o'])
        for lock in ('judge-05-k1.lock', 'worker-05-k5.lock'):    # taken again, and anew
            append(os.path.join(self.cache, lock), '')
        _, after = self.watch()
        self.assertEqual(cache_tampering(self.cache, before, after), [])

    def test_copy_takes_the_files_git_knows(self):
        append(os.path.join(self.repo, 'chapters/06-new.md'), 'not added yet\n')
        copy = os.path.join(os.path.dirname(self.repo), 'copy')
        copy_book(self.repo, copy)
        self.assertEqual(sorted(os.path.relpath(p, copy) for p in tree_files(copy, ())), [
            '.gitignore', 'Makefile', 'chapters/05-a.md', 'chapters/06-new.md',
            'log.test', 'tests/ch05/test_a.cpp', 'tests/hidden/ch05/test_b.cpp',
            'tools/grading/grade.py'])

    def test_copy_outside_git_takes_the_tree_but_build_and_bytecode(self):
        shutil.rmtree(os.path.join(self.repo, '.git'))
        copy = os.path.join(os.path.dirname(self.repo), 'copy')
        copy_book(self.repo, copy)
        self.assertEqual(sorted(os.path.relpath(p, copy) for p in tree_files(copy, ())), [
            '.gitignore', 'Makefile', 'chapters/05-a.md', 'log.test',
            'tests/ch05/test_a.cpp', 'tests/hidden/ch05/test_b.cpp', 'tools/grading/grade.py'])


if __name__ == '__main__':
    unittest.main()


class SandboxUidTest(unittest.TestCase):
    """Graders running at once give their workers different uids, so that
    one student's fork bomb cannot use up the process limit of another's
    worker (seen in a batch: the other worker's sandbox failed to start)."""

    def test_graders_running_at_once_take_different_uids(self):
        code = ('import sys, time; sys.path.insert(0, %r); from tools.grading import sandbox; '
                'print(sandbox.sandbox_uid(), flush=True); time.sleep(3)'
                % ROOT)
        first = subprocess.Popen([sys.executable, '-c', code], stdout=subprocess.PIPE,
                                 text=True)
        second = subprocess.Popen([sys.executable, '-c', code], stdout=subprocess.PIPE,
                                  text=True)
        uids = {int(first.stdout.readline()), int(second.stdout.readline())}
        first.wait()
        second.wait()
        first.stdout.close()
        second.stdout.close()
        self.assertEqual(len(uids), 2, uids)
