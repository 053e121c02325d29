#!/usr/bin/env python3
"""Run GoogleTest binaries and the tools' own tests; print one summary.

    tools/testing/runtests.py [--python-tests DIR_OR_FILE ...] [LABEL=BINARY ...]

Each binary runs with a time limit and writes a JSON report; a test counts as
passed only when that report says so, so a binary that dies midway loses its
remaining tests instead of passing them. A binary's tests are split into
GoogleTest shards (GTEST_TOTAL_SHARDS), and --jobs shards of all the binaries
run at a time: the tests are independent processes' work, so they use every
core. Each file of Python tests runs in a process of its own, in the same
pool and ahead of the shards, so that the tools' slow tests (builds of kits,
graders, the benchmark) run side by side instead of one after another while
a core waits. A binary whose bytes equal an earlier one's runs once: the code
as of chapter 6 often links a chapter's tests into exactly the program that
the code as of chapter 5 did (nothing they use changed), and the same program
in the same environment gives the same results, which are then reported
under both labels. The last line, "tests: N passed, M failed", is the one CI
reads; it adds ", K skipped" when tests were skipped, each listed above it
with what it said (a course's kit skips the tests that reach a later
assignment's stub, tests/calls/rpc.h).
"""
import argparse
import concurrent.futures
import hashlib
import json
import os
import re
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(os.path.dirname(HERE)))  # the repository: import tools.*
from tools.testing import gtest  # noqa: E402

TIME_LIMIT = 900  # seconds for one test binary; a hang must not stall CI


def skip_reason(output, test):
    """What a skipped test said (GTEST_SKIP's message, which brief output
    prints after "FILE:LINE: Skipped"; the JSON report does not hold it)."""
    match = re.search(r'^%s:%d: Skipped\n(.*)$' % (re.escape(test.get('file', '')),
                                                   test.get('line', 0)), output, re.M)
    return match.group(1) if match else 'no reason given'


def run_shard(binary, index, total):
    """Runs one shard of a GoogleTest binary: (output, exit status, its test
    suites or None)."""
    env = dict(os.environ, GTEST_TOTAL_SHARDS=str(total), GTEST_SHARD_INDEX=str(index))
    return gtest.run(binary, ['--gtest_brief=1'], env=env, timeout=TIME_LIMIT)


def summarize(label, binary, shards, same_as=None):
    """Returns (passed, failed names, skipped names with their reasons) for one
    binary from its shards' results (those of the identical binary labelled
    same_as, if given)."""
    passed, failed, skipped = 0, [], []
    for output, code, suites in shards:
        if suites is None:
            print(output)
            print('%s: %s ended (%s) without a report: counted as one failure'
                  % (label, binary, code))
            failed.append(label + ' (no report)')
            continue
        shard_failed = []
        for suite, test in gtest.tests(suites):
            if test.get('result') == 'SKIPPED':
                skipped.append('%s %s.%s: %s' % (label, suite, test['name'],
                                                 skip_reason(output, test)))
            if not gtest.ran(test):
                continue
            if test.get('failures'):
                shard_failed.append('%s %s.%s' % (label, suite, test['name']))
            else:
                passed += 1
        if shard_failed or code != 0:
            print(output)
            if not shard_failed:  # exited non-zero after all tests passed (a leak report, say)
                shard_failed.append('%s (exit status %s)' % (label, code))
        failed += shard_failed
    print('%-28s %5d passed, %d failed%s%s' % (
        label, passed, len(failed), ', %d skipped' % len(skipped) if skipped else '',
        ' (the program of %s)' % same_as if same_as else ''))
    return passed, failed, skipped


def content_key(binary):
    """The binary's bytes, hashed; a missing one is its own key (and fails)."""
    try:
        with open(binary, 'rb') as f:
            return hashlib.sha256(f.read()).hexdigest()
    except OSError:
        return 'missing:' + binary


def submit_gtests(pool, binaries, jobs):
    """Submits every binary in `jobs` shards; returns (label, binary, shards,
    label of the identical binary whose shards they are, or None)."""
    first = {}  # content key -> (label, shards) of the first binary with it
    runs = []
    for label, binary in binaries:
        key = content_key(binary)
        if key not in first:
            first[key] = (label, [pool.submit(run_shard, binary, index, jobs)
                                  for index in range(jobs)])
        first_label, shards = first[key]
        runs.append((label, binary, shards, None if first_label == label else first_label))
    return runs


def python_test_files(path):
    """The files of Python tests in a directory, or the one file given (a
    chapter's program, say)."""
    if os.path.isfile(path):
        return [path]
    return sorted(os.path.join(path, name) for name in os.listdir(path)
                  if name.startswith('test') and name.endswith('.py'))


def run_python_file(path):
    """Runs one file's tests in a Python of its own, so that files run side by
    side and one that crashes or exits takes nothing else with it:
    (output, exit status, report or None)."""
    return gtest.run_with_report(lambda report: [sys.executable, os.path.abspath(__file__),
                                                 '--python-report', report, path])


def write_python_report(path, report):
    """In the child: runs the tests of the file `path` and writes what passed
    and failed to `report`."""
    directory, pattern = os.path.dirname(path), os.path.basename(path)
    suite = unittest.defaultTestLoader.discover(directory, pattern=pattern,
                                                top_level_dir=directory)
    result = unittest.TextTestRunner(verbosity=1, stream=sys.stdout).run(suite)
    failed = ['tools %s' % test.id() for test, _ in result.failures + result.errors]
    with open(report, 'w') as f:
        json.dump({'passed': result.testsRun - len(failed) - len(result.skipped),
                   'failed': failed}, f)


def summarize_python(path, output, code, report):
    """(passed, failed names) of one file's tests, its output printed."""
    label = 'tools/' + os.path.basename(path)
    print(output, end='' if output.endswith('\n') else '\n')
    if report is None:
        print('%s: ended (%s) without a report: counted as one failure' % (label, code))
        return 0, [label + ' (no report)']
    print('%-28s %5d passed, %d failed' % (label, report['passed'], len(report['failed'])))
    return report['passed'], report['failed']


def main():
    parser = argparse.ArgumentParser()
    # Repeatable: make test CH=09 names two files, and each must run.
    parser.add_argument('--python-tests', action='append', default=[],
                        help='a directory of test*.py files, or one file (repeatable)')
    parser.add_argument('--python-report', help=argparse.SUPPRESS)
    parser.add_argument('--jobs', type=int, default=os.cpu_count() or 1)
    parser.add_argument('binaries', nargs='*', metavar='LABEL=BINARY')
    args = parser.parse_args()
    if args.python_report:
        write_python_report(args.binaries[0], args.python_report)
        return
    jobs = max(1, args.jobs)
    binaries = [item.split('=', 1) for item in args.binaries]
    files = [f for path in args.python_tests for f in python_test_files(path)]
    passed, failed, skipped = 0, [], []
    # One pool for all: the Python files first, as they take longest (they
    # build kits, graders, the benchmark), then the binaries' shards.
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        python_runs = [(path, pool.submit(run_python_file, path)) for path in files]
        gtest_runs = submit_gtests(pool, binaries, jobs)
        for path, future in python_runs:
            p, f = summarize_python(path, *future.result())
            passed, failed = passed + p, failed + f
        for label, binary, shards, same_as in gtest_runs:
            p, f, s = summarize(label, binary, [f.result() for f in shards], same_as)
            passed, failed, skipped = passed + p, failed + f, skipped + s
    for name in skipped:
        print('SKIPPED:', name)
    for name in failed:
        print('FAILED:', name)
    print('tests: %d passed, %d failed%s' % (passed, len(failed),
                                             ', %d skipped' % len(skipped) if skipped else ''))
    sys.exit(1 if failed or passed == 0 else 0)


if __name__ == '__main__':
    main()
