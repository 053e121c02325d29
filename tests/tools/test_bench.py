"""Tests of chapter 6's benchmark program, bench/bvhbench.cpp, as a user runs
it: options that select only part of the benchmarks must give a clear
message, never a crash.

The program is built with `make bench-build` (the same rule `make` uses), in
the default configuration: the make that runs these tests may carry
SANITIZE=1 or FLOAT=double, which the benchmark is not built for, so its
variables are kept out of the inner make. The program makes its own data
from data/bunny.ply (3,674 triangles); nothing here measures time.
"""
import glob
import os
import subprocess
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def last_chapter_number():
    chapters = sorted(glob.glob(os.path.join(ROOT, 'chapters', '[0-9][0-9]-*.md')))
    return os.path.basename(chapters[-1])[:2]


def has_benchmark():
    """Whether a chapter of this book writes the benchmark (a kit of the
    chapters before 6 has none: tools/bench.mk then builds nothing)."""
    for path in glob.glob(os.path.join(ROOT, 'chapters', '[0-9][0-9]-*.md')):
        with open(path, encoding='utf-8') as f:
            if '\n<<bench/bvhbench.cpp>>=\n' in f.read():
                return True
    return False


@unittest.skipUnless(has_benchmark(), 'no chapter of this book writes the benchmark')
class BenchProgramTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        env = {k: v for k, v in os.environ.items()
               if k not in ('MAKEFLAGS', 'MFLAGS', 'MAKELEVEL', 'MAKEOVERRIDES',
                            'SANITIZE', 'FLOAT', 'BUILD', 'CH', 'UPTO')}
        build = subprocess.run(['make', '--no-print-directory', 'bench-build'],
                               cwd=ROOT, env=env, capture_output=True, text=True)
        if build.returncode != 0:
            raise AssertionError('make bench-build failed:\n' + build.stdout +
                                 build.stderr)
        cls.binary = os.path.join(ROOT, 'build', 'float', 'asof',
                                  last_chapter_number(), 'bench', 'bvhbench')

    def run_bench(self, benchmark_filter):
        with tempfile.TemporaryDirectory() as tmp:
            return subprocess.run(
                [self.binary, '--data', os.path.join(tmp, 'none'),
                 '--mesh', 'data/bunny.ply', '--methods', 'sah',
                 '--passes', '1', '--builds', '1',
                 '--json', os.path.join(tmp, 'out.json'),
                 '--benchmark_filter=' + benchmark_filter,
                 '--benchmark_color=false'],
                cwd=ROOT, capture_output=True, text=True, timeout=300)

    def test_adopted_without_first_is_an_error_not_a_crash(self):
        # The adopted tree is a copy of the first version's: a filter that
        # leaves out the first version's build left a null pointer behind.
        r = self.run_bench('adopted')
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("the adopted version copies the first version's tree, "
                      "which was not built", r.stdout)
        self.assertIn('--benchmark_filter', r.stdout)

    def test_adopted_with_first_traces_the_same_hits(self):
        r = self.run_bench('first|adopted')
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertNotIn('ERROR OCCURRED', r.stdout)
        hits = {}
        for line in r.stdout.splitlines():
            # rows of the ray tables: method, version, Mrays/s, hits,
            # sum of t (and the check against the references, if any)
            fields = line.split()
            if len(fields) in (5, 6) and fields[0] == 'SAH' and \
                    fields[1] in ('first', 'adopted') and 'e+' in fields[4]:
                hits.setdefault(fields[1], []).append(int(fields[3]))
        # one row per ray set and version: the camera rays and the
        # incoherent rays that the program generates
        self.assertEqual(len(hits.get('first', [])), 2, r.stdout)
        self.assertEqual(hits['first'], hits['adopted'])
        self.assertGreater(min(hits['first']), 0)


if __name__ == '__main__':
    unittest.main()
