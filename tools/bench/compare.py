#!/usr/bin/env python3
"""Measure several compiler configurations of the benchmark side by side.

    tools/bench/compare.py [--rounds N] [--out DIR] [--args ARGS] \\
        "g++ -O2" "g++ -O3" "g++ -O3 -march=native" "clang++ -O3"

Each configuration is a compiler command and its optimization flags, as
`make bench BENCH_CXX=... BENCH_CXXFLAGS=...` takes them. The script builds
every configuration's program first (make bench-build), then runs the
programs in turn, N rounds (default 10) of one run each, the order rotated
by one configuration every round: a slow spell of the machine then falls on
every configuration alike, rather than on whichever happened to run in it.
Each run writes DIR/<configuration>/round-NN.json (default DIR:
build/bench-compare); at the end tools/bench/table.py --configurations turns
all of them into one table, the medians over the rounds, on stdout.

ARGS are the program's options for every run (default: the SAH trees, one
pass of the first and the final version, one build). Everything else (the
data, the warnings, the directory per configuration) is make bench's.
"""
import argparse
import os
import shlex
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the repository
DEFAULT_ARGS = '--methods sah --passes 1 --builds 1 --benchmark_filter=first|final'


def configuration(text):
    words = text.split()
    if not words:
        raise argparse.ArgumentTypeError('an empty configuration')
    return words[0], ' '.join(words[1:]) or '-O2'


def make(*args, capture=False):
    """Runs make in the repository; its output goes to stderr, so that
    stdout holds only the table."""
    r = subprocess.run(['make', '--no-print-directory', '-C', ROOT] + list(args),
                       stdout=subprocess.PIPE if capture else sys.stderr, text=True)
    if r.returncode != 0:
        sys.exit('bench_compare: make %s failed' % ' '.join(map(shlex.quote, args)))
    return r.stdout


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('configurations', nargs='+', type=configuration,
                   metavar='"COMPILER FLAGS..."')
    p.add_argument('--rounds', type=int, default=10)
    p.add_argument('--out', default=os.path.join(ROOT, 'build', 'bench-compare'))
    p.add_argument('--args', default=DEFAULT_ARGS)
    opt = p.parse_args()
    if opt.rounds < 1:
        p.error('--rounds must be at least 1')

    programs = []
    for cxx, flags in opt.configurations:
        config = ['BENCH_CXX=' + cxx, 'BENCH_CXXFLAGS=' + flags]
        make('bench-build', *config)
        make('bench-data', *config)
        program, data = make('-s', 'bench-path', *config, capture=True).split()
        name = '%s %s' % (cxx, flags)
        out = os.path.join(opt.out, ''.join(c if c.isalnum() or c in '.+-' else '_'
                                            for c in name))
        os.makedirs(out, exist_ok=True)
        for old in os.listdir(out):
            if old.startswith('round-') and old.endswith('.json'):
                os.remove(os.path.join(out, old))
        programs.append((name, os.path.join(ROOT, program),
                         os.path.join(ROOT, data), out))

    files = []
    for r in range(opt.rounds):
        k = r % len(programs)
        for name, program, data, out in programs[k:] + programs[:k]:
            json_file = os.path.join(out, 'round-%02d.json' % (r + 1))
            print('bench_compare: round %d of %d: %s' % (r + 1, opt.rounds, name),
                  file=sys.stderr, flush=True)
            run = subprocess.run([program, '--data', data, '--json', json_file] +
                                 shlex.split(opt.args),
                                 stdout=subprocess.DEVNULL)
            if run.returncode != 0:
                sys.exit('bench_compare: %s: round %d failed (exit %d)'
                         % (name, r + 1, run.returncode))
            files.append(json_file)
    # One row per configuration, in the order given.
    files.sort(key=lambda f: ([p[3] for p in programs].index(os.path.dirname(f)), f))
    table = subprocess.run([sys.executable, os.path.join(ROOT, 'tools', 'bench', 'table.py'),
                            '--configurations'] + files)
    sys.exit(table.returncode)


if __name__ == '__main__':
    main()
