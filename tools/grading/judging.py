"""Judging one exercise: the chapter's judge (the book's code and tests,
tests/calls/judge.cpp) runs the exercise's tests against a worker that
holds the student's code, and the tests' statuses come from the judge's
records (records.py); verdicts are kept in the cache by what decided them
(judge_exercise)."""
import hashlib
import json
import os
import shutil
import signal
import subprocess
import tempfile
import time

from tools.grading import records
from tools.grading import sandbox
from tools.grading.files import atomic_write, write_private

# The form of the verdicts kept in the cache (part of their key): verdicts
# kept by a grader that read the judge otherwise are not taken.
RECORDS = 'records-1'

def judge_exercise(args, judge, worker, results, secret):
    """Runs the judge on the tests of one exercise (results) against its
    worker, and fills in their statuses from the judge's own report. The
    verdicts of a judge and a worker (both named by their contents in the
    cache) on the same cases are the same: they are kept, and a submission
    whose code for the exercise is the same as an earlier one's gets them
    without running again (except timeouts, which depend on the machine)."""
    key = hashlib.sha256('\0'.join([RECORDS, judge, worker, str(secret),
                                     repr(args.time_limit), str(args.memory_limit),
                                     str(args.cpu_limit)] +
                                    [r.full for r in results]).encode()).hexdigest()[:32]
    kept = os.path.join(args.cache, 'verdicts-%s.json' % key)
    try:
        with open(kept, encoding='utf-8') as f:
            verdicts = [(v, records.failures(fs)) for v, fs in json.load(f)]
        if len(verdicts) != len(results) or any(v not in records.VERDICTS
                                                for v, _ in verdicts):
            raise ValueError('not the verdicts of these tests')
        for r, (verdict, failures) in zip(results, verdicts):
            r.judged(verdict, failures)
        return
    except (OSError, ValueError, TypeError):
        pass
    run_judge(args, judge, worker, results, secret)
    if all(r.status in ('PASS', 'FAIL', 'CRASH', 'OOM') for r in results):
        atomic_write(kept, json.dumps([[r.status, r.failures] for r in results]))


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


def end_the_run(judge_run):
    """Ends the judge and whatever it started. A judge killed at the
    exercise's deadline ends none of its workers: without namespaces nothing
    else would (bubblewrap's die-with-parent does in the sandbox), and a
    worker spinning in the student's code would run on, an orphan, until its
    CPU limit, slowing the gradings after it. Its process group (the judge's
    session) holds the workers the judge started; a root grader's workers run
    as the sandbox's user, which holds nothing else of this grader's while no
    judge runs, so every process of that user is ended too (a worker cannot
    leave the group: its system-call filter refuses setsid and fork). What
    the dead judge left came to this grader (sandbox.adopt_orphans), which
    reaps it."""
    try:
        os.killpg(judge_run.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass        # the judge ended, and every worker with it
    judge_run.communicate()
    if sandbox.isolation() == 'unprivileged user':
        sandbox.end_processes_of(sandbox.sandbox_uid())
    sandbox.reap_orphans()


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
        # The judge's verdicts are in its report; what it prints (GoogleTest
        # prints every failed check, and a worker can make millions) is not
        # read, and held in a pipe it would grow the grader without limit.
        judge_run = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                     stderr=subprocess.DEVNULL, start_new_session=True,
                                     preexec_fn=sandbox.judge_process(args.judge_memory_limit))
        try:
            judge_run.communicate(timeout=left)
            ended = None if judge_run.returncode in (0, 1) else \
                'the judge ended with status %d' % judge_run.returncode
        except subprocess.TimeoutExpired:
            pass
        finally:
            end_the_run(judge_run)
    found = records.read_report(report)
    for r in results:
        if r.full not in found:
            r.status = 'NOT-RUN' if ended is None else 'TIMEOUT'
            r.message = ended or 'the judge has no test %s' % r.full
            continue
        r.judged(*found[r.full])

