"""What a submission can make the grader hold is limited (docs/grading.md):
a compile of a student's code within --compile-time-limit, the judge's
memory and the verdicts whatever the student's code throws, and the cache
keys name every byte of what a build reads.

The grading cases grade chapter 5 with ex-5.10's region changed, in both
isolation modes: bubblewrap, and the fallback without namespaces (a `bwrap`
on PATH that fails, as where a container forbids namespaces)."""
import glob
import io
import json
import os
import shutil
import subprocess
import sys
import tarfile
import tempfile
import threading
import time
import unittest
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.dirname(os.path.dirname(HERE)))
import test_grade as tg  # noqa: E402
from tools.exercises import markup  # noqa: E402
from tools.grading import build as grade_build, judging, records, sandbox, structure, submission  # noqa: E402
from tools.grading.grade import structure_note  # noqa: E402
from tools.grading.report import Report, Result  # noqa: E402

# ex-5.10's region, after the book's solution lines.
SOLUTION = 'Float invD = invDir[i];\nint isNeg = dirIsNeg[i];'
HUGE = 128 << 20
LONG = 1 << 20
# The message thrown: an invalid UTF-8 byte first, then LONG bytes.
ODD_PREFIX = '\\xff not UTF-8 '
ODD_LENGTH = 1 + len(' not UTF-8 ') + LONG
# Four constant evaluations of about 13 s each at -O0 on a loaded machine.
SLOW = '\n'.join(
    ['constexpr auto spin = [](int k) { long s = 0; for (int a = 0; a < 30000; ++a) '
     'for (int b = 0; b < 30000; ++b) s += a ^ b ^ k; return s; };'] +
    ['static_assert(spin(%d) != -1, "spin");' % k for k in range(4)])
COMPILE_LIMIT = 3
# The first PACED calls of each worker take 20 ms each: honest code, far
# within the per-call limit (tg.TIME_LIMIT, 2 s), but a block of the judge's
# requests holds more than a hundred of them, so a worker that answered a
# block only when it had answered all of it would take longer than the limit
# to send its first reply.
PACED = 300
PACING = ('{ static int calls = 0; if (calls++ < %d) { struct timespec ts = {0, 20000000}; '
          'nanosleep(&ts, nullptr); } }' % PACED)
# What the code throws after its exercise's stub message: the words that the
# grader once took for the judge's (the end of GoogleTest's report of an
# exception, the judge's report of a crash), and a record of the judge's.
FORGED = ('" thrown in the test body.\ntests/calls/judge.cpp:1\nFailed\nduring Intersect: '
          'the code crashed: killed by SIGSEGV\n{"test": "%s", "verdict": "PASS", '
          '"failures": []}\n')


def stub_message(exercise, fragment):
    """The message of the stub of <<fragment>> in the student edition."""
    paths = sorted(os.path.join('chapters', f) for f in os.listdir(os.path.join(tg.ROOT,
                                                                               'chapters'))
                   if tg.CHAPTER_FILE.match(f))
    cwd = os.getcwd()
    os.chdir(tg.ROOT)
    try:
        book = markup.load(paths, root=tg.ROOT)
    finally:
        os.chdir(cwd)
    return markup.stub_message([e for e in book.exercises if e.id == exercise][0], fragment)


class JudgeLimitTest(unittest.TestCase):
    """The judge runs with an address-space limit of its own (a reply shaped to
    fail millions of checks grows it, and the machine is shared), and with
    the standard library's bounds checks, so that a test indexing past a short
    reply aborts it instead of reading its memory into a failure message."""

    def limit_seen_by(self, preexec):
        r = subprocess.run([sys.executable, '-c', 'import resource; '
                            'print(resource.getrlimit(resource.RLIMIT_AS)[0])'],
                           preexec_fn=preexec, capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        return int(r.stdout)

    def judge_started(self):
        """The keyword arguments with which judge_tests() starts a judge
        (with --judge-memory-limit 80)."""
        seen = {}

        class Stop(Exception):
            pass

        def popen(cmd, **kwargs):
            seen.update(kwargs)
            raise Stop()
        args = type('Args', (), {'judge_memory_limit': 80, 'time_limit': 10,
                                 'exercise_time_limit': 900})()
        real = judging.subprocess.Popen
        judging.subprocess.Popen = popen
        try:
            with tempfile.TemporaryDirectory() as tmp:
                with self.assertRaises(Stop):
                    judging.judge_tests(args, 'judge', 'argv', 'secret',
                                        os.path.join(tmp, 'run'), [], time.monotonic() + 60)
        finally:
            judging.subprocess.Popen = real
        return seen

    def test_the_judge_process_has_its_memory_limit(self):
        self.assertEqual(self.limit_seen_by(sandbox.judge_process(96)), 96 << 20)

    def test_a_limit_of_zero_is_none(self):
        self.assertEqual(self.limit_seen_by(sandbox.judge_process(0)),
                         self.limit_seen_by(None))

    def test_the_judge_is_started_with_the_limit_of_its_option(self):
        seen = {'preexec': self.judge_started()['preexec_fn']}
        self.assertEqual(self.limit_seen_by(seen['preexec']), 80 << 20)

    def test_what_the_judge_prints_is_not_kept(self):
        # A worker can make the judge print millions of failed checks; the
        # grader, which has no memory limit, must not hold them.
        seen = self.judge_started()
        self.assertIs(seen['stdout'], subprocess.DEVNULL)
        self.assertIs(seen['stderr'], subprocess.DEVNULL)

    def test_the_judge_is_built_with_bounds_checks(self):
        self.assertIn('-D_GLIBCXX_ASSERTIONS', grade_build.JUDGE_CXXFLAGS)
        # and they work in a program built with those flags: an index past
        # the end of a vector aborts
        with tempfile.TemporaryDirectory() as tmp:
            src = os.path.join(tmp, 'past.cpp')
            with open(src, 'w') as f:
                f.write('#include <vector>\nint main(int argc, char **) {\n'
                        '    std::vector<int> v(1);\n    return v[argc + 3];\n}\n')
            subprocess.run(['g++'] + grade_build.JUDGE_CXXFLAGS + [src, '-o', src + '.bin'],
                           check=True)
            r = subprocess.run([src + '.bin'], capture_output=True)
        self.assertEqual(r.returncode, -6)


class CacheKeyTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix='lrt-grade-keys-')

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def write(self, rel, text):
        path = os.path.join(self.tmp, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, 'w', encoding='utf-8') as f:
            f.write(text)

    def test_a_line_directive_of_the_student_is_in_the_worker_key(self):
        self.write('a/lrt/x.cpp', 'int x = __LINE__;\n')
        self.write('b/lrt/x.cpp', '#line 7\nint x = __LINE__;\n')
        self.assertNotEqual(grade_build.tree_hash(os.path.join(self.tmp, 'a')),
                            grade_build.tree_hash(os.path.join(self.tmp, 'b')))

    def test_every_tool_of_the_tangle_is_in_the_judge_key(self):
        self.write('chapters/05-x.md', 'text\n')
        self.write('tests/ch05/t.cpp', '\n')
        for tool in grade_build.TANGLE_TOOLS:
            self.write(tool, '# %s\n' % tool)
        for tool in grade_build.TANGLE_TOOLS:
            before = grade_build.judge_key(self.tmp, '05')
            self.write(tool, '# %s, changed\n' % tool)
            self.assertNotEqual(grade_build.judge_key(self.tmp, '05'), before, tool)

    def test_an_earlier_chapters_test_headers_are_in_the_judge_key(self):
        # Chapter 7's tests include chapter 6's headers (its scenes, checks
        # and exercise calls); a later chapter's are no input of the judge.
        for rel in ('chapters/06-x.md', 'chapters/07-y.md', 'chapters/08-z.md',
                    'tests/ch06/checks.h', 'tests/ch07/t.cpp', 'tests/ch08/later.h'):
            self.write(rel, '// %s\n' % rel)
        before = grade_build.judge_key(self.tmp, '07')
        self.write('tests/ch06/checks.h', '// changed\n')
        changed = grade_build.judge_key(self.tmp, '07')
        self.assertNotEqual(changed, before)
        self.write('tests/ch08/later.h', '// changed\n')
        self.assertEqual(grade_build.judge_key(self.tmp, '07'), changed)

    def test_a_worker_copies_the_calls_of_the_chapters_up_to_its_own(self):
        for n in ('05', '06', '07'):
            self.write('tests/ch%s/exercise_calls.h' % n, '\n')
        files = grade_build.call_files(self.tmp, '06')
        self.assertEqual([f for f in files if not f.startswith('tests/calls/')],
                         ['tests/ch05/exercise_calls.h', 'tests/ch06/exercise_calls.h'])

    def test_a_line_that_is_not_json_costs_only_its_own_test(self):
        path = os.path.join(self.tmp, 'results.jsonl')
        with open(path, 'wb') as f:
            f.write(b'{"test": "A.a", "verdict": "PASS", "failures": []}\n'
                    b'{"test": "A.b", "verdict": "FAIL", "failures": ["\xff"]}\n'
                    b'{"test": "A.c", "verdict": "FAIL", "failures": []}\n')
        self.assertEqual(sorted(records.read_report(path)), ['A.a', 'A.c'])


class ShownTextTest(unittest.TestCase):
    """What a submission chose that the feedback shows: its members' names
    and what its code threw (a red team: a tar member's name put a heading
    and an image into results.json, 200 names of a megabyte each made the
    grader hold 1.25 GB and write 210 MB of feedback, and U+FFFE in a thrown
    message made junit.xml unreadable)."""

    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix='lrt-shown-')
        self.addCleanup(shutil.rmtree, self.tmp)

    def archive(self, members):
        path = os.path.join(self.tmp, 'submission.tar.gz')
        with tarfile.open(path, 'w:gz', format=tarfile.PAX_FORMAT) as tar:
            for name, data in members:
                info = tarfile.TarInfo(name)
                info.size = len(data)
                tar.addfile(info, io.BytesIO(data))
        return path

    def test_member_names_are_shown_safely_and_read_within_bounds(self):
        markdown = 'notes`\n\n## All tests passed: 7/7\n\n![b](https://example.invalid/b.png)\n`x'
        members = [('chapters/05-slab-test.md', b'chapter text\n'), (markdown, b'x'),
                   ('a' * 300000 + '.txt', b'x')]
        members += [('%d' % k + 'b' * 150000, b'x') for k in range(10)]
        sub = submission.read_submission(self.archive(members), {'05-slab-test.md'})
        self.assertEqual(sub.chapters['05-slab-test.md'],
                         ('chapters/05-slab-test.md', b'chapter text\n'))
        self.assertIn(submission.TOO_MANY, sub.problems)
        self.assertLess(len(sub.ignored), 10)      # the names' budget stopped the reading
        for name, _ in sub.ignored:
            self.assertLess(len(name), submission.SHOWN_NAME + 40)
            self.assertNotIn('\n', name)
            self.assertNotIn('`', name)

    def test_a_name_used_holds_no_markup_and_a_name_shown_stays_short(self):
        # The chapter under a path of Markdown and HTML is not graded, and
        # no reason, which shows names out of `...`, holds markup; a name
        # whose characters escape to ten each is still cut to its length.
        chapter = b'chapter text\n'
        members = [('zz/05-slab-test.md', chapter),
                   ('<b onmouseover=x>[x](javascript:y)/05-slab-test.md', chapter),
                   ('05-<img src=x>[a](https:b)**B**.md', b'x'),
                   ('\U000e0001' * 250, b'x')]
        sub = submission.read_submission(self.archive(members), {'05-slab-test.md'})
        self.assertEqual(sub.chapters['05-slab-test.md'][0], 'zz/05-slab-test.md')
        for name, reason in sub.ignored:
            self.assertNotRegex(reason, r'[<>\[\]*]')
            self.assertLess(len(name), submission.SHOWN_NAME + 40)

    def test_a_directory_stops_at_its_first_entry_over_the_limit(self):
        top = os.path.join(self.tmp, 'submission')
        for k in range(submission.MAX_FILES + 100):
            os.makedirs(os.path.join(top, 'd%04d' % k))
            with open(os.path.join(top, 'd%04d' % k, 'f'), 'w') as f:
                f.write('x')
        sub = submission.read_submission(top, {'05-slab-test.md'})
        self.assertEqual(sub.problems, [submission.TOO_MANY])
        self.assertLessEqual(len(sub.ignored), submission.MAX_FILES)

    def test_a_thrown_message_keeps_junit_xml_well_formed(self):
        r = Result('ex-5.10', '05', 'Ex5_10_Slab', 'Odd', False, 1.0, '')
        r.judged('FAIL', [{'kind': 'threw', 'call': '',
                           'message': 'odd \ufffe\uffff\ud800 characters'}])
        report = Report(self.tmp, 'odd')
        report.exercises.append(('05', 'ex-5.10', 1.0))
        report.results.append(r)
        suites = ET.fromstring(report.junit())
        self.assertIn('odd ??? characters', ''.join(suites.itertext()))


class StructureLimitTest(unittest.TestCase):
    """A chapter can make a structure problem of every line: a solution
    region of fragment uses (a red team's submission) gave one line of
    feedback per 6 bytes, 45 MB of results.json and 384 MB in the grader for
    1.2 MB of such lines. The problems listed are capped and counted."""
    LINES = 5000

    def test_the_problems_listed_are_capped_and_counted(self):
        text = tg.read(os.path.join(tg.ROOT, tg.CHAPTER))
        bomb = '\n'.join(['<<a>>'] * self.LINES)
        tmp = tempfile.mkdtemp(prefix='lrt-structure-')
        try:
            path = os.path.join(tmp, os.path.basename(tg.CHAPTER))
            with open(path, 'w', encoding='utf-8') as f:
                f.write(tg.replace_region(text, tg.F10, bomb))
            cwd = os.getcwd()
            os.chdir(tg.ROOT)
            try:
                reference, _ = structure.parse_chapter(tg.CHAPTER)
                student, _ = structure.parse_chapter(path)
            finally:
                os.chdir(cwd)
        finally:
            shutil.rmtree(tmp, ignore_errors=True)
        problems, changes, _ = structure.check_structure(reference, student, tg.CHAPTER)
        self.assertEqual(len(problems), structure.MAX_LISTED + 1)
        self.assertIn('<<a>>', problems[0])
        more = self.LINES - structure.MAX_LISTED
        self.assertEqual(problems[-1], '... and %d more problems' % more)
        self.assertLessEqual(len(changes), structure.MAX_LISTED + 1)

    def test_new_chunks_are_compared_once(self):
        # Renamed exercise chunks among many new ones: each new chunk's
        # skeleton is made once, not once per missing exercise chunk (a red
        # team's chapter of 153,000 new chunks kept grade.py busy for hours).
        text = tg.read(os.path.join(tg.ROOT, 'chapters/03-shapes.md'))
        for name in ('Offset p along n to the side of w',
                     'Round offset point po away from p'):
            text = text.replace('<<%s>>=' % name, '<<renamed %s>>=' % name, 1)
        text += ''.join('```cpp\n<<new %d>>=\n@\n```\n' % k for k in range(2000))
        tmp = tempfile.mkdtemp(prefix='lrt-structure-')
        calls = []
        real = structure.skeleton
        try:
            path = os.path.join(tmp, '03-shapes.md')
            with open(path, 'w', encoding='utf-8') as f:
                f.write(text)
            cwd = os.getcwd()
            os.chdir(tg.ROOT)
            try:
                reference, _ = structure.parse_chapter('chapters/03-shapes.md')
                student, _ = structure.parse_chapter(path)
            finally:
                os.chdir(cwd)
            structure.skeleton = lambda *a: calls.append(1) or real(*a)
            problems, _, _ = structure.check_structure(reference, student, 'x.md')
        finally:
            structure.skeleton = real
            shutil.rmtree(tmp, ignore_errors=True)
        self.assertIn('was renamed to <<renamed Offset p along n', problems[0])
        # Once per chunk of either chapter, and once per missing exercise
        # chunk of the book.
        chunks = len(reference.chunks) + len(student.chunks)
        self.assertLessEqual(len(calls), chunks + 2)

    def test_a_long_message_is_cut(self):
        listed = structure.Listed()
        listed.append('x' * 100000)
        self.assertLess(len(listed[0]), structure.MAX_MESSAGE + 40)
        self.assertTrue(listed[0].endswith('... (100000 characters)'))

    def test_a_chunk_name_cannot_bring_markdown_into_the_feedback(self):
        # Names quoted in a problem are the student's: a link, an image or
        # bold text in one must stay text, in a code span it cannot close.
        name = '![pixel](https://example.org/p.png) [click](https://example.org) **PASSED** `x`'
        line = structure_note('chapters/05.md:9: in <<F>>: fragment use <<%s>>' % name)
        self.assertTrue(line.startswith('- `') and line.endswith('`'))
        self.assertNotIn('`', line[3:-1])
        self.assertIn('![pixel](https://example.org/p.png)', line)


class PeakMemory:
    """The largest VmHWM (kB) of the processes running `binary` while it
    lives, polled every 20 ms (the judge keeps what it accepted until its
    test ends)."""
    def __init__(self, directory):
        self.directory, self.peak, self.done = directory, 0, False
        self.thread = threading.Thread(target=self.poll)
        self.thread.start()

    def poll(self):
        while not self.done:
            for pid in filter(str.isdigit, os.listdir('/proc')):
                try:
                    if not os.readlink('/proc/%s/exe' % pid).startswith(self.directory):
                        continue
                    with open('/proc/%s/status' % pid) as f:
                        for line in f:
                            if line.startswith('VmHWM:'):
                                self.peak = max(self.peak, int(line.split()[1]))
                except OSError:
                    continue
            time.sleep(0.02)

    def stop(self):
        self.done = True
        self.thread.join()
        return self.peak


class LimitsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        owner, points = tg.chapter5()
        cls.target = owner[tg.F10]
        cls.others = {e: p for e, p in points.items() if e != cls.target}
        cls.tmp = tempfile.mkdtemp(prefix='lrt-grade-limits-')
        cls.cache = os.path.join(cls.tmp, 'cache')
        text = tg.read(os.path.join(tg.ROOT, tg.CHAPTER))
        cls.stub = stub_message(cls.target, tg.F10)
        forged = cls.stub + FORGED % 'Ex5_10_X.Y'
        for name, code in (
                # Once per worker process: replies to a whole batch of such
                # calls would only exhaust the worker's own memory.
                ('huge', '{ static bool sent = false; if (!sent) { sent = true; '
                         'throw std::runtime_error(std::string(%d, \'x\')); } }' % HUGE),
                ('odd', 'throw std::runtime_error(std::string("%s") + std::string(%d, '
                        '\'y\'));' % (ODD_PREFIX, LONG)),
                ('forged', 'throw std::runtime_error(%s);' % json.dumps(forged)),
                ('slow', SLOW + '\n' + SOLUTION),
                ('paced', PACING + '\n' + SOLUTION)):
            tg.put_chapter(cls.tmp, name, tg.replace_region(text, tg.F10, code)
                           if name in ('slow', 'paced') else tg.inject(text, tg.F10, code))
        cls.no_bwrap = tg.failing_bwrap(os.path.join(cls.tmp, 'no-bwrap'))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def grade(self, name, fallback, *options):
        """(results.json, the judge's peak kB, seconds) of grading `name`."""
        mode = 'unprivileged user' if fallback else 'bubblewrap'
        out = os.path.join(self.tmp, 'out-%s-%s' % (name, mode.split()[0]))
        env = dict(os.environ)
        if fallback:
            env['PATH'] = self.no_bwrap + os.pathsep + env['PATH']
        memory = PeakMemory(self.cache)
        start = time.monotonic()
        try:
            proc = subprocess.run(
                [sys.executable, tg.GRADE, '--cache', self.cache, '--out', out,
                 '--chapters', '05', '--time-limit', str(tg.TIME_LIMIT)] + list(options) +
                [os.path.join(self.tmp, name)],
                cwd=tg.ROOT, env=env, capture_output=True, text=True, timeout=900)
        finally:
            peak = memory.stop()
        elapsed = time.monotonic() - start
        self.assertEqual(proc.returncode, 0, proc.stderr)
        with open(os.path.join(out, 'results.json'), encoding='utf-8') as f:
            results = json.load(f)
        self.assertIn(mode, results['output'])
        self.assertLess(os.path.getsize(os.path.join(out, 'results.json')), 200 << 10)
        for test in results['tests']:
            if test['name'].split()[0] != self.target:
                self.assertEqual(test['status'], 'passed', (test['name'], test['output']))
        return results, peak, elapsed

    def target_tests(self, results):
        tests = [t for t in results['tests'] if t['name'].split()[0] == self.target]
        self.assertTrue(tests)
        for test in tests:
            self.assertEqual(test['status'], 'failed', test['name'])
            self.assertEqual(test['score'], 0)
        return tests

    def check_huge(self, fallback):
        # Time to make and send 128 MB on a loaded machine.
        results, peak, _ = self.grade('huge', fallback, '--time-limit', '20')
        print('judge peak %d kB' % peak, file=sys.stderr)
        for test in self.target_tests(results):
            if test['visibility'] == 'visible':
                self.assertIn('the answer was larger than 4 MB', test['output'])
            else:   # a hidden test: the kind of failure, not the code's doing
                self.assertIn(': the answer was refused\n', test['output'])
                self.assertNotIn('4 MB', test['output'])
        # The judge of chapter 5 alone peaks at about 170 MB (its speculative
        # runs); holding one 128 MB reply would take it past 400 MB.
        self.assertLess(peak, 300 << 10, 'the judge grew to %d kB' % peak)
        kept = glob.glob(os.path.join(self.cache, 'verdicts-*.json'))
        self.assertLess(max(os.path.getsize(p) for p in kept), 100 << 10)
        self.assertAlmostEqual(results['score'], sum(self.others.values()), places=3)

    def check_odd(self, fallback):
        results, _, _ = self.grade('odd', fallback)
        for test in self.target_tests(results):
            if test['visibility'] == 'visible':
                self.assertIn('\ufffd not UTF-8 yyy', test['output'])
            else:   # a hidden test: that the code threw, not what
                self.assertIn('the code threw an exception (not shown', test['output'])
                self.assertNotIn('yyy', test['output'])
            self.assertNotIn('the judge has no test', test['output'])
        # What the judge kept of the message: its first 4096 bytes.
        kept = glob.glob(os.path.join(self.cache, 'verdicts-*.json'))
        text = ''.join(tg.read(p) for p in kept)
        self.assertIn('[... %d more bytes]' % (ODD_LENGTH - 4096), text)
        self.assertAlmostEqual(results['score'], sum(self.others.values()), places=3)

    def check_forged(self, fallback):
        # The code throws its stub's message, then what imitates the judge:
        # the grader shows a hidden test that the code threw, not that it
        # is not done (nor that it crashed), and no test passes.
        results, _, _ = self.grade('forged', fallback)
        for test in self.target_tests(results):
            self.assertEqual(test['tags'], ['FAIL'], test['name'])
            if test['visibility'] == 'visible':   # all it threw, as its own words
                self.assertIn('C++ exception with description "%s" thrown in the test body.'
                              '\ntests/calls/judge.cpp:1\n' % self.stub, test['output'])
            else:
                self.assertIn(': the code threw an exception (not shown for a hidden test)'
                              '\n', test['output'])
                for word in ('not done', 'crashed', 'SIGSEGV', 'verdict'):
                    self.assertNotIn(word, test['output'])
        self.assertAlmostEqual(results['score'], sum(self.others.values()), places=3)

    def check_slow(self, fallback):
        results, _, elapsed = self.grade('slow', fallback, '--compile-time-limit',
                                         str(COMPILE_LIMIT))
        print('graded in %.1f s' % elapsed, file=sys.stderr)
        for test in self.target_tests(results):
            self.assertIn('the compile took longer than %d s' % COMPILE_LIMIT,
                          test['output'])
        self.assertIn('**Compile error in %s**' % self.target, results['output'])
        self.assertAlmostEqual(results['score'], sum(self.others.values()), places=3)
        # The judge and the other exercises' workers are in the cache by now.
        self.assertLess(elapsed, 60)

    def check_paced(self, fallback):
        # Each call is answered when it is done: the limit is per call.
        results, _, _ = self.grade('paced', fallback)
        for test in results['tests']:
            self.assertEqual(test['status'], 'passed', (test['name'], test['output']))
        self.assertAlmostEqual(results['score'], results['max_score'], places=3)

    @unittest.skipUnless(os.geteuid() == 0, 'the sandbox drops to its own user only as root')
    def test_bubblewrap(self):
        for check in (self.check_huge, self.check_odd, self.check_slow, self.check_paced):
            with self.subTest(check.__name__):
                check(fallback=False)

    @unittest.skipUnless(os.geteuid() == 0, 'the sandbox drops to its own user only as root')
    def test_a_thrown_message_cannot_pass_for_the_judges_words(self):
        self.check_forged(fallback=False)

    @unittest.skipUnless(os.geteuid() == 0, 'the fallback needs root')
    def test_fallback_without_namespaces(self):
        for check in (self.check_huge, self.check_odd, self.check_slow, self.check_paced):
            with self.subTest(check.__name__):
                check(fallback=True)


if __name__ == '__main__':
    unittest.main()
