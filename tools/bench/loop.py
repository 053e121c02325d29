#!/usr/bin/env python3
"""Time a student's edit-test loop: the wall and CPU time of make commands.

    tools/bench/loop.py [--dir CHECKOUT] [--runs 5] [--clean-clone]

Three measurements, each the median of --runs runs, in CHECKOUT (default: this
repository, or a kit):

  unchanged   `make test CH=05` when nothing changed since the last run
  edited      `make test CH=05` after an edit in ex-5.9's fragment, which every
              test of chapter 5 includes: a statement with no effect, different
              at every run so that no build cache has seen it; the chapter is
              restored afterwards
  clean       (--clean-clone) `make test` in a fresh clone of CHECKOUT's
              committed state, with an empty compiler cache, as on a new machine

CPU time (user + system of every process the command ran) is given beside the
wall time: it depends less on what else the machine is doing. The report names
the python3 that make runs: the loop starts it several times, and a python3
behind a version manager's shim (pyenv) takes about 0.3 s longer to start than
Debian's.
"""
import argparse
import glob
import os
import random
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the repository
FRAGMENT = '<<Compute the reciprocal direction and its sign on axis i>>='


def timed(command, cwd, env=None):
    """Runs a command; returns (wall seconds, CPU seconds of its processes)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    proc = subprocess.run(command, cwd=cwd, env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        sys.exit('bench_loop: %s failed in %s:\n%s'
                 % (' '.join(command), cwd, proc.stdout[-3000:]))
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def chapter_five(checkout):
    paths = glob.glob(os.path.join(checkout, 'chapters', '05-*.md'))
    if len(paths) != 1:
        sys.exit('bench_loop: no single chapters/05-*.md in %s' % checkout)
    return paths[0]


def edit_fragment(path, text):
    """Returns the chapter's text with a no-op statement in ex-5.9's fragment."""
    lines = text.split('\n')
    for i, line in enumerate(lines):
        if line.strip() == FRAGMENT:
            lines.insert(i + 1, '(void)0x%x;' % random.getrandbits(48))
            return '\n'.join(lines)
    sys.exit('bench_loop: %s has no fragment %s' % (path, FRAGMENT))


def median_of(runs, measure):
    samples = [measure() for _ in range(runs)]
    return (statistics.median(w for w, _ in samples),
            statistics.median(c for _, c in samples))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--dir', default=ROOT)
    parser.add_argument('--runs', type=int, default=5)
    parser.add_argument('--clean-clone', action='store_true')
    args = parser.parse_args()
    checkout = os.path.abspath(args.dir)
    make_ch05 = ['make', 'test', 'CH=05']
    results = []

    timed(make_ch05, checkout)  # brings the build up to date
    results.append(('unchanged: make test CH=05',
                    median_of(args.runs, lambda: timed(make_ch05, checkout))))

    path = chapter_five(checkout)
    with open(path) as f:
        original = f.read()

    def edited():
        with open(path, 'w') as f:
            f.write(edit_fragment(path, original))
        return timed(make_ch05, checkout)
    try:
        results.append(('edited ex-5.9: make test CH=05', median_of(args.runs, edited)))
    finally:
        with open(path, 'w') as f:
            f.write(original)
    timed(make_ch05, checkout)  # the build again as the chapter is

    if args.clean_clone:
        def clean():
            with tempfile.TemporaryDirectory() as tmp:
                clone = os.path.join(tmp, 'clone')
                subprocess.run(['git', 'clone', '-q', checkout, clone], check=True)
                env = dict(os.environ, CCACHE_DIR=os.path.join(tmp, 'ccache'))
                return timed(['make', 'test'], clone, env)
        results.append(('clean clone: make test', median_of(args.runs, clean)))

    load = os.getloadavg()[0]
    print('%s, medians of %d runs, load average %.1f at the end, python3 is %s'
          % (checkout, args.runs, load, os.path.realpath(shutil.which('python3'))))
    print('%-34s %10s %10s' % ('command', 'wall (s)', 'CPU (s)'))
    for name, (wall, cpu) in results:
        print('%-34s %10.1f %10.1f' % (name, wall, cpu))


if __name__ == '__main__':
    main()
