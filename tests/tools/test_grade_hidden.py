"""Nothing a student sees of a grading carries a hidden test's inputs, and
no process of the machine can read the grading's secret (docs/grading.md).

- A chapter-5 submission whose ex-5.10 records the arguments of every call
  it answers (in a static string) and throws all it has recorded, in every
  call. Were one worker to answer both the public and the hidden tests, a
  public test that ran after a hidden one would show the hidden test's
  inputs as the message of what the code threw; and a hidden test's own
  failure would show them as well. Neither may happen, while a public test
  still shows what the code threw.
- While that submission is graded, no process's command line or
  environment (/proc/PID/cmdline, /proc/PID/environ) holds the secret
  (given with --seed, in a flags file so that the grader's own command line
  does not hold it either) or the GoogleTest seed derived from it.

Graded by a scratch copy of the repository, in both isolation modes:
bubblewrap, and the fallback without namespaces (a `bwrap` on PATH that
fails, as where a container forbids namespaces), where a student's worker
runs beside the grader and can read every command line of the machine."""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import test_grade as tg  # noqa: E402

# ex-5.10's region (<<Look up the reciprocal direction and its sign on axis
# i>>, in the form of the slab test that a BVH calls): once per call, every
# argument, as std::to_string prints it, added to what it has seen, and all
# of it thrown.
RECORDER = r'''static std::string lrtSeen;   // every argument of every call so far
if (i == 0) {
    auto f = [](Float x) { return std::to_string(x); };
    lrtSeen += "box=(" + f(b.pMin.x) + "," + f(b.pMin.y) + "," + f(b.pMin.z) + ")-(" +
               f(b.pMax.x) + "," + f(b.pMax.y) + "," + f(b.pMax.z) + ") o=(" +
               f(ray.o.x) + "," + f(ray.o.y) + "," + f(ray.o.z) + ") d=(" +
               f(ray.d.x) + "," + f(ray.d.y) + "," + f(ray.d.z) + ") tMax=" +
               f(ray.tMax) + " invDir=(" + f(invDir.x) + "," + f(invDir.y) + "," +
               f(invDir.z) + ") dirIsNeg=(" + std::to_string(dirIsNeg[0]) + "," +
               std::to_string(dirIsNeg[1]) + "," + std::to_string(dirIsNeg[2]) + ")\n";
    throw std::runtime_error(lrtSeen);
}
Float invD = invDir[i];
int isNeg = dirIsNeg[i];'''

# The hidden tests of ex-5.10 (tests/hidden/ch05/test_ex5_hidden.cpp) aim
# rays at the unit box from 0.5 -+ 2 d, d's components in {-1, -0, +0, 1};
# its public test's ray starts at (0.5, 0.5, -1). The origins' coordinates
# that only the hidden tests use, as the recorder prints them:
HIDDEN_SOURCE = os.path.join(tg.ROOT, 'tests', 'hidden', 'ch05', 'test_ex5_hidden.cpp')
HIDDEN_EXPRESSIONS = ('Point3f toward(Float(0.5) - 2 * dx', 'Point3f away(Float(0.5) + 2 * dx')
PUBLIC_ORIGIN = (0.5, 0.5, -1)
HIDDEN_ONLY = sorted({'%f' % (0.5 + sign * 2 * c) for sign in (-1, 1) for c in (-1, 0, 1)
                      if 0.5 + sign * 2 * c not in PUBLIC_ORIGIN})    # -1.500000, 2.500000
# What the recorder prints of the public test's call.
PUBLIC_CALL = 'o=(0.500000,0.500000,-1.000000)'
CALL = 'BoxIntersectPWithInverse'

# The secret: under it, the tests of ex-5.10 in one shuffled run (as they
# were before the public and the hidden ones got workers of their own) run
# the hidden suite first, so that before that split the public test's
# message carried the hidden inputs. GoogleTest's seed is SECRET % 99999 + 1.
SECRET = 99999 * 123456789 + 86420
GTEST_SEED = SECRET % 99999 + 1


class ProcessWatch:
    """Reads every process's command line and environment, over and over,
    while a grading runs: the processes in which a pattern was found, and
    how many judges and workers were seen (so that the watch cannot pass
    without having looked at them)."""
    def __init__(self, patterns):
        self.patterns = patterns     # {label: compiled bytes regex}
        self.found, self.seen, self.judges, self.workers = [], set(), set(), set()
        self.done = False
        self.thread = threading.Thread(target=self.poll)
        self.thread.start()

    def poll(self):
        while not self.done:
            for pid in filter(str.isdigit, os.listdir('/proc')):
                for what in ('cmdline', 'environ'):
                    try:
                        with open('/proc/%s/%s' % (pid, what), 'rb') as f:
                            data = f.read()
                    except OSError:
                        continue
                    if what == 'cmdline':
                        args = data.split(b'\0')
                        if any(a.startswith(b'--lrt-results=') for a in args):
                            self.judges.add(pid)
                        if args[0].endswith(b'/worker'):
                            self.workers.add(pid)
                    for label, pattern in self.patterns.items():
                        if (label, pid, what) not in self.seen and pattern.search(data):
                            self.seen.add((label, pid, what))
                            self.found.append((label, pid, what, data[:2000]))
            time.sleep(0.005)

    def stop(self):
        self.done = True
        self.thread.join()


def number(n):
    """n as a decimal number in a command line or an environment, not as
    part of a longer one."""
    return re.compile(rb'(?<![0-9])%d(?![0-9])' % n)


@unittest.skipUnless(os.geteuid() == 0, 'the sandbox drops to its own user, and the '
                     'fallback runs, only as root')
class HiddenInputsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        owner, cls.points = tg.chapter5()
        cls.target = owner[tg.F10]
        cls.tmp = tempfile.mkdtemp(prefix='lrt-grade-hidden-')
        cls.copy = os.path.join(cls.tmp, 'repo')
        tg.copy_book(tg.ROOT, cls.copy)
        text = tg.read(os.path.join(cls.copy, tg.CHAPTER))
        tg.put_chapter(cls.tmp, 'recorder', tg.replace_region(text, tg.F10, RECORDER))
        cls.no_bwrap = tg.failing_bwrap(os.path.join(cls.tmp, 'no-bwrap'))
        # --seed in a flags file: the grader's own command line holds only
        # the file's name.
        cls.flags = os.path.join(cls.tmp, 'flags')
        with open(cls.flags, 'w') as f:
            f.write('--seed\n%d\n' % SECRET)
        cls.gradings = {}

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def grading(self, fallback):
        """(process, output directory, watch) of grading the recorder in a
        mode, once per mode."""
        mode = 'unprivileged user' if fallback else 'bubblewrap'
        if mode not in self.gradings:
            out = os.path.join(self.tmp, 'out-' + mode.split()[0])
            env = dict(os.environ, PYTHONDONTWRITEBYTECODE='1')
            if fallback:
                env['PATH'] = self.no_bwrap + os.pathsep + env['PATH']
            watch = ProcessWatch({'the secret': number(SECRET),
                                  'the GoogleTest seed': number(GTEST_SEED)})
            try:
                proc = subprocess.run(
                    [sys.executable, os.path.join(self.copy, 'tools', 'grading', 'grade.py'),
                     '--cache', os.path.join(self.tmp, 'cache-' + mode.split()[0]),
                     '--out', out, '--chapters', '05', '--time-limit', str(tg.TIME_LIMIT),
                     '@' + self.flags, os.path.join(self.tmp, 'recorder')],
                    cwd=self.copy, env=env, capture_output=True, text=True, timeout=1800)
            finally:
                watch.stop()
            self.gradings[mode] = (proc, out, watch)
        proc, out, watch = self.gradings[mode]
        self.assertEqual(proc.returncode, 0, proc.stderr)
        with open(os.path.join(out, 'results.json'), encoding='utf-8') as f:
            results = json.load(f)
        self.assertIn(mode, results['output'])
        self.assertEqual(results['extra_data']['secret'], SECRET)
        return proc, out, results, watch

    def check_hidden_inputs(self, fallback):
        proc, out, results, _ = self.grading(fallback)
        source = tg.read(HIDDEN_SOURCE)
        for expression in HIDDEN_EXPRESSIONS:     # the inputs are still those
            self.assertIn(expression, source)
        self.assertEqual(HIDDEN_ONLY, ['-1.500000', '2.500000'])
        # Nowhere: not in any file of the results, not on the grader's output.
        texts = {name: tg.read(os.path.join(out, name)) for name in sorted(os.listdir(out))}
        texts.update(stdout=proc.stdout, stderr=proc.stderr)
        self.assertEqual(sorted(n for n in texts if n not in ('stdout', 'stderr')),
                         ['junit.xml', 'results.json', 'results.txt'])
        for where, text in texts.items():
            for value in HIDDEN_ONLY:
                self.assertNotIn(value, text, where)
        # The public test shows what the code threw: the public call's
        # arguments. A hidden test, that the code threw in the call, no more.
        tests = [t for t in results['tests'] if t['name'].split()[0] == self.target]
        public = [t for t in tests if t['visibility'] == 'visible']
        hidden = [t for t in tests if t['visibility'] == 'after_published']
        self.assertTrue(public and hidden)
        for test in public:
            self.assertEqual(test['tags'], ['FAIL'])
            self.assertIn('C++ exception with description "box=', test['output'])
            self.assertIn(PUBLIC_CALL, test['output'])
        for test in hidden:
            self.assertEqual(test['tags'], ['FAIL'])
            self.assertIn('```\nduring %s: the code threw an exception (not shown for a '
                          'hidden test)\n```' % CALL, test['output'])
            self.assertNotIn('box=', test['output'])
        for test in results['tests']:
            if test['name'].split()[0] != self.target:
                self.assertEqual(test['tags'], ['PASS'], test['name'])
        self.assertAlmostEqual(results['score'], sum(self.points.values()) -
                               self.points[self.target], places=3)

    def check_secret(self, fallback):
        _, _, _, watch = self.grading(fallback)
        self.assertEqual([(label, pid, what, data.replace(b'\0', b' ').decode(
            'utf-8', 'replace')) for label, pid, what, data in watch.found], [])
        # The watch saw the processes it is about.
        self.assertTrue(watch.judges)
        self.assertTrue(watch.workers)

    def test_hidden_inputs_with_bubblewrap(self):
        self.check_hidden_inputs(fallback=False)

    def test_hidden_inputs_without_namespaces(self):
        self.check_hidden_inputs(fallback=True)

    def test_no_secret_in_any_process_with_bubblewrap(self):
        self.check_secret(fallback=False)

    def test_no_secret_in_any_process_without_namespaces(self):
        self.check_secret(fallback=True)


if __name__ == '__main__':
    unittest.main()
