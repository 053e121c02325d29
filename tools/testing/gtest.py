"""Running a GoogleTest binary and reading what its JSON report says.

    output, code, suites = gtest.run(binary, ['--gtest_brief=1'], env, timeout)
    for suite, test in gtest.tests(suites): ...

A test counts as passed only when the report says so: a binary that dies
midway writes none (suites is None), and loses its remaining tests instead
of passing them. Used by tools/testing/runtests.py (make test) and by the
exercise kits' validation and try (through tools/exercises/kit_common.py).
"""
import json
import os
import subprocess
import tempfile


def run_with_report(command, env=None, timeout=None):
    """Runs command(report), a command that writes a JSON report to the path
    `report`: (output, exit status or 'timeout', the report, or None if none
    was written)."""
    with tempfile.TemporaryDirectory() as tmp:
        report = os.path.join(tmp, 'report.json')
        try:
            proc = subprocess.run(command(report), capture_output=True, text=True,
                                  timeout=timeout, env=env)
            output, code = proc.stdout + proc.stderr, proc.returncode
        except subprocess.TimeoutExpired as e:
            output, code = (e.stdout or b'').decode(errors='replace'), 'timeout'
        try:
            with open(report) as f:
                return output, code, json.load(f)
        except (OSError, ValueError):
            return output, code, None


def run(binary, args=(), env=None, timeout=None):
    """Runs a GoogleTest binary with `args`: (output, exit status or
    'timeout', its test suites as the JSON report lists them, or None if it
    wrote no report)."""
    output, code, report = run_with_report(
        lambda report: [binary] + list(args) + ['--gtest_output=json:' + report],
        env=env, timeout=timeout)
    return output, code, report.get('testsuites') if isinstance(report, dict) else None


def tests(suites):
    """(suite name, test) for every test of the report's suites."""
    for suite in suites:
        for test in suite['testsuite']:
            yield suite['name'], test


def ran(test):
    """Whether the test ran: neither skipped (GTEST_SKIP) nor filtered out."""
    return test.get('result') != 'SKIPPED' and test.get('status') != 'NOTRUN'


def failure_text(failed):
    """The failure messages of a test, or of every test of a report's suites."""
    if isinstance(failed, dict):
        return '\n'.join(f.get('failure', '') for f in failed.get('failures', []))
    return '\n'.join(failure_text(test) for _, test in tests(failed) if test.get('failures'))


def list_tests(binary, env=None):
    """(suite, name) of every test of the binary, as --gtest_list_tests names
    them (a binary that dies still lists its tests)."""
    listing = subprocess.run([binary, '--gtest_list_tests'], capture_output=True, text=True,
                             env=env).stdout
    names, suite = [], None
    for line in listing.splitlines():
        if not line.strip():
            continue
        if not line.startswith(' '):
            suite = line.split('#')[0].strip().rstrip('.')
        else:
            names.append((suite, line.split('#')[0].strip()))
    return names
