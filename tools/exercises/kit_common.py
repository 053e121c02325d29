"""What the exercise kits' build, leak check, validation and try share
(tools/exercises/kits.py and the modules it runs): the repository, the two
editions, failing with a message, running a kit's make and its test binaries
in an environment of their own, and reading the source's book.
"""
import glob
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, ROOT)  # the repository: import tools.*
from tools.exercises import markup  # noqa: E402
from tools.testing import gtest  # noqa: E402

EDITIONS = ('solution', 'student')
# Make variables of the calling make that must not leak into a kit's make.
MAKE_ENV_DROP = ('CHAPTERS', 'BUILD', 'MAKEFLAGS', 'MFLAGS', 'MAKELEVEL', 'MAKEOVERRIDES',
                 'CH', 'UPTO', 'ONLY', 'ASOF', 'HIDDEN', 'GTEST_FILTER')
TIME_LIMIT = 600        # seconds for one test binary


def shown(path):
    """A path as relative to the current directory, if it is below it."""
    rel = os.path.relpath(path)
    return path if rel.startswith('..') else rel


def fail(message):
    sys.exit('exercises: ' + message)


def stop_on(problems, message):
    """Prints the problems, if any, and fails with message (which takes
    their count, %d)."""
    for problem in problems:
        print(problem, file=sys.stderr)
    if problems:
        fail(message % len(problems))


def clean_env():
    env = {k: v for k, v in os.environ.items() if k not in MAKE_ENV_DROP}
    env['LC_ALL'] = 'C'
    return env


def make(kit, args, capture=True):
    cmd = ['make', '--no-print-directory', '-C', kit] + args
    proc = subprocess.run(cmd, env=clean_env(), capture_output=capture, text=True)
    return proc


def source_book(src):
    paths = sorted(glob.glob(os.path.join(src, 'chapters', '[0-9][0-9]-*.md')))
    if not paths:
        fail('no chapters in %s/chapters' % src)
    rel = [os.path.relpath(p, src) for p in paths]
    cwd = os.getcwd()
    os.chdir(src)    # the book's messages name chapters as the lint does
    try:
        book = markup.Book(rel, root='.')
    finally:
        os.chdir(cwd)
    if not markup.report_errors(book):
        fail('fix the errors above first (make lint)')
    return book


def read_bytes(path):
    with open(path, 'rb') as f:
        return f.read()


def run_gtest(binary, gtest_filter=None, timeout=TIME_LIMIT):
    """(output, exit status, suites or None) of the binary's tests (those
    that gtest_filter names, if given), run in the kits' environment."""
    output, code, suites = gtest.run(
        binary, ['--gtest_filter=' + gtest_filter] if gtest_filter else [],
        env=clean_env(), timeout=timeout)
    if code == 'timeout':
        return 'timed out after %d s' % timeout, code, None
    return output, code, suites
