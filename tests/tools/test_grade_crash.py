"""What one exercise's code does costs no other exercise a point, and
nothing of it outlives the grading (docs/grading.md).

- A chapter-5 submission whose ex-5.9 calls exit(0) in every call, and
  whose other exercises are the book's code, must score exactly the other
  exercises' points, however many workers the crashing exercise goes
  through.
- One whose ex-5.9 is the book's code but starts a setsid() daemon in each
  of its workers must score full points, and no daemon may be left.
- One whose ex-5.9 spins for ever, graded with less time for the exercise
  than for one call, so that the grader kills the judge while a worker
  spins: the worker must end with its judge, not run on as an orphan.

The grader runs here under a parent that never reaps orphans, as in a
container whose first process is no init: whatever the sandboxes leave
behind stays there, counts against the sandbox user's process limit, and is
counted by the test. Both isolation modes: bubblewrap, and the fallback
without namespaces (a `bwrap` on PATH that fails, as where a container
forbids namespaces)."""
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import test_grade as tg  # noqa: E402

# Runs the grader as a child subreaper that never waits for anything but the
# grader: every process that a grading leaves becomes its child, and is
# listed, alive or a zombie, once the grading is over.
NEVER_REAPS = r'''
import ctypes, json, os, subprocess, sys
PR_SET_CHILD_SUBREAPER = 36
ctypes.CDLL(None).prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0)
grader = subprocess.Popen(sys.argv[1:], stdout=subprocess.DEVNULL)
def judge_running():
    # A judge that the grader started (not another grading's).
    for pid in filter(str.isdigit, os.listdir('/proc')):
        try:
            with open('/proc/%s/stat' % pid) as f:
                name, fields = f.read().split(' (', 1)[1].rsplit(') ', 1)
        except (OSError, ValueError, IndexError):
            continue
        if name == 'judge' and int(fields.split()[1]) == grader.pid:
            return True
    return False
if os.environ.get('LRT_KILL_THE_GRADER'):
    # Killed outright once its judge has run a while, as a batch's time
    # limit or an outer timeout kills it: it can end nothing itself.
    import signal, time
    while grader.poll() is None and not judge_running():
        time.sleep(0.2)
    time.sleep(5)
    grader.send_signal(signal.SIGKILL)
    grader.wait()
    time.sleep(5)
    status = 0
else:
    status = grader.wait()
left = []
for pid in filter(str.isdigit, os.listdir('/proc')):
    try:
        with open('/proc/%s/stat' % pid) as f:
            fields = f.read().rsplit(')', 1)[1].split()
    except OSError:
        continue
    if int(fields[1]) == os.getpid():
        left.append(pid + ' ' + fields[0])
print(json.dumps({'status': status, 'left': left}))
'''


# The daemon, in system calls through libc's syscall (the exercise's code can
# include no header and write no asm; syscall is declared after the book's
# header, so the call is made one that argument-dependent lookup finds when
# the template is instantiated, as tests/tools/attacks.py does): once per
# worker, fork; the child leaves the session (setsid), takes a name the test
# looks for (prctl PR_SET_NAME) and waits for ever. The worker's system call
# filter now refuses the fork; the judge's reaping stands behind it.
DAEMON = 'lrtdaemon'
START_DAEMON = r"""{
  static int lrtStarted = 0;
  if (!lrtStarted) {
    lrtStarted = 1;
    auto lrtCall = [](auto global, long n, long a, long b) -> long {
      return syscall(n, a, b, global);
    };
    long lrtPid = lrtCall(::div_t{}, 57L, 0, 0);
    if (lrtPid == 0) {
      static const char lrtName[16] = "%s";
      lrtCall(::div_t{}, 112L, 0, 0);
      lrtCall(::div_t{}, 157L, 15L, (long)lrtName);
      for (;;) lrtCall(::div_t{}, 34L, 0, 0);
    }
  }
}""" % DAEMON


def daemons():
    """The pids of the daemons that are still there."""
    return tg.processes_named(DAEMON)


class CrashInOneExerciseTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        owner, cls.points = tg.chapter5()
        cls.crashing = owner[tg.F9]
        cls.tmp = tempfile.mkdtemp(prefix='lrt-grade-crash-')
        book_chapter = tg.read(os.path.join(tg.ROOT, tg.CHAPTER))
        for name, code in (('exits', 'std::exit(0);'), ('daemon', START_DAEMON),
                           ('spins', 'for (volatile long lrtSpin = 0;; lrtSpin = lrtSpin + 1) {}')):
            tg.put_chapter(cls.tmp, name, tg.inject(book_chapter, tg.F9, code))
        cls.no_bwrap = tg.failing_bwrap(os.path.join(cls.tmp, 'no-bwrap'))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def grade(self, submission, mode, fallback, options=(), kill=False):
        """Grades the submission in the mode; its results.json, once it is
        checked that nothing of the grading is left."""
        out = os.path.join(self.tmp, 'out', submission, mode)
        env = dict(os.environ)
        if fallback:
            env['PATH'] = self.no_bwrap + os.pathsep + env['PATH']
        if kill:
            env['LRT_KILL_THE_GRADER'] = '1'
        proc = subprocess.run(
            [sys.executable, '-c', NEVER_REAPS, sys.executable, tg.GRADE,
             '--cache', os.path.join(self.tmp, 'cache-' + mode), '--out', out,
             '--chapters', '05', '--time-limit', str(tg.TIME_LIMIT)] + list(options) +
            [os.path.join(self.tmp, submission)],
            cwd=tg.ROOT, env=env, capture_output=True, text=True)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        ended = json.loads(proc.stdout)
        for line in ended['left']:     # a failed test leaves no process behind
            try:
                os.kill(int(line.split()[0]), 9)
            except OSError:
                pass
        self.assertEqual(ended['status'], 0, proc.stderr)
        if kill:
            # What the killed grader started is this harness's now, which
            # reaps nothing: none of it may still run (zombies it must have).
            self.assertEqual([p for p in ended['left'] if not p.endswith(' Z')], [])
            self.assertEqual(daemons(), [])
            return None
        # Nothing of the grading is left: no process and no zombie.
        self.assertEqual(ended['left'], [])
        self.assertEqual(daemons(), [])
        with open(os.path.join(out, 'results.json'), encoding='utf-8') as f:
            results = json.load(f)
        self.assertIn(mode, results['output'])
        return results

    def check_exits(self, mode, fallback):
        results = self.grade('exits', mode, fallback)
        for test in results['tests']:
            exercise = test['name'].split()[0]
            if exercise == self.crashing:
                self.assertEqual(test['status'], 'failed', test['name'])
                self.assertIn('CRASH', test['output'], test['name'])
            else:
                self.assertEqual(test['status'], 'passed', (test['name'], test['output']))
        others = sum(p for e, p in self.points.items() if e != self.crashing)
        self.assertAlmostEqual(results['score'], others, places=3)

    def check_daemon(self, mode, fallback):
        results = self.grade('daemon', mode, fallback)
        self.assertAlmostEqual(results['score'], sum(self.points.values()), places=3)

    def check_spins(self, mode, fallback):
        # Each call may take 60 s, the exercise 10 s in all: the grader kills
        # the judge while its worker spins in the first call.
        results = self.grade('spins', mode, fallback,
                             ['--time-limit', '60', '--exercise-time-limit', '10'])
        for test in results['tests']:
            if test['name'].split()[0] == self.crashing:
                self.assertIn('TIMEOUT', test['output'], test['name'])

    def check_killed_grader(self, mode, fallback):
        self.grade('spins', mode, fallback,
                   ['--time-limit', '60', '--exercise-time-limit', '60'], kill=True)

    @unittest.skipUnless(os.geteuid() == 0, 'the sandbox drops to its own user only as root')
    def test_killed_grader_leaves_nothing_running_in_bubblewrap(self):
        self.check_killed_grader('bubblewrap', fallback=False)

    @unittest.skipUnless(os.geteuid() == 0, 'the fallback needs root')
    def test_killed_grader_leaves_nothing_running_without_namespaces(self):
        self.check_killed_grader('unprivileged user', fallback=True)

    @unittest.skipUnless(os.geteuid() == 0, 'the sandbox drops to its own user only as root')
    def test_spinning_worker_ends_with_its_judge_in_bubblewrap(self):
        self.check_spins('bubblewrap', fallback=False)

    @unittest.skipUnless(os.geteuid() == 0, 'the fallback needs root')
    def test_spinning_worker_ends_with_its_judge_without_namespaces(self):
        self.check_spins('unprivileged user', fallback=True)

    @unittest.skipUnless(os.geteuid() == 0, 'the sandbox drops to its own user only as root')
    def test_bubblewrap(self):
        self.check_exits('bubblewrap', fallback=False)

    @unittest.skipUnless(os.geteuid() == 0, 'the fallback needs root')
    def test_fallback_without_namespaces(self):
        self.check_exits('unprivileged user', fallback=True)

    @unittest.skipUnless(os.geteuid() == 0 and platform.machine() == 'x86_64',
                         'root, and the daemon\'s x86-64 system calls')
    def test_daemon_with_bubblewrap(self):
        self.check_daemon('bubblewrap', fallback=False)

    @unittest.skipUnless(os.geteuid() == 0 and platform.machine() == 'x86_64',
                         'root, and the daemon\'s x86-64 system calls')
    def test_daemon_without_namespaces(self):
        self.check_daemon('unprivileged user', fallback=True)


sys.path.insert(0, tg.ROOT)
from tools.grading import sandbox  # noqa: E402


@unittest.skipUnless(os.geteuid() == 0, 'only a root grader runs its sandboxes as their own user')
class UidLeftoversTest(unittest.TestCase):
    """A grader that was killed outright ended nothing: what its student left
    runs on as the sandbox's uid, which the next grader takes."""

    def test_ending_the_processes_of_a_uid(self):
        # The last uid of the range, which no grader takes while fewer than
        # 256 run.
        uid = sandbox.SANDBOX_UIDS[-1]
        left = subprocess.Popen(['setpriv', '--reuid=%d' % uid, '--regid=%d' % uid,
                                 '--clear-groups', '--', 'sleep', '600'])
        self.addCleanup(left.kill)
        # Once it runs as the uid (setpriv starts as root).
        while True:
            with open('/proc/%d/status' % left.pid) as f:
                if 'Uid:\t%d\t' % uid in f.read():
                    break
            time.sleep(0.01)
        sandbox.end_processes_of(uid)
        self.assertEqual(left.wait(timeout=10), -9)
        sandbox.end_processes_of(uid)    # none left: no error either

    def test_graders_with_other_temporary_directories_take_other_uids(self):
        # As the autograder's test runs one, in a private /tmp: before, it
        # took the uid of a grader running beside it, and killed its workers.
        code = ('import sys, time; sys.path.insert(0, %r); from tools.grading import sandbox; '
                'print(sandbox.sandbox_uid(), flush=True); time.sleep(3)'
                % tg.ROOT)
        graders = []
        for _ in range(2):
            env = dict(os.environ, TMPDIR=tempfile.mkdtemp(dir=self.tmp))
            graders.append(subprocess.Popen([sys.executable, '-c', code], env=env,
                                            stdout=subprocess.PIPE, text=True))
        uids = {int(g.stdout.readline()) for g in graders}
        for g in graders:
            g.wait()
            g.stdout.close()
        self.assertEqual(len(uids), 2, uids)

    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix='lrt-uid-test-')
        self.addCleanup(shutil.rmtree, self.tmp)

    def test_a_grader_ends_what_its_uid_left_before_it_uses_it(self):
        ended = []
        real = sandbox.end_processes_of
        sandbox.end_processes_of = ended.append
        try:
            uid = sandbox.sandbox_uid.__wrapped__()
        finally:
            sandbox.end_processes_of = real
        self.assertEqual(ended, [uid])


if __name__ == '__main__':
    unittest.main()
