"""Tests of the benchmark of Appendix A, bench/bvhbench.cpp and its make rules
(tools/make/bench.mk), as a user runs them: options that select only part of the
benchmarks must give a clear message, never a crash; a configuration of
compiler and flags builds the library and the program with them, in a
directory of its own, and is named in the table and the JSON; an unknown
compiler is a clear error; tools/bench/table.py turns the JSON of several
configurations into one table.

The program is built with `make bench-build` (the same rule `make` uses), in
the default configuration: the make that runs these tests may carry
SANITIZE=1 or FLOAT=double, which the benchmark is not built for, so its
variables are kept out of the inner make. The program makes its own data
from data/bunny.ply (3,674 triangles); nothing here measures time.
"""
import glob
import json
import os
import re
import struct
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
MAKE_VARIABLES = ('MAKEFLAGS', 'MFLAGS', 'MAKELEVEL', 'MAKEOVERRIDES', 'SANITIZE',
                  'FLOAT', 'BUILD', 'CH', 'UPTO', 'BENCH_CXX', 'BENCH_CXXFLAGS')


def last_chapter_number():
    chapters = sorted(glob.glob(os.path.join(ROOT, 'chapters', '[0-9][0-9]-*.md')))
    return os.path.basename(chapters[-1])[:2]


def has_benchmark():
    """Whether a chapter of this book writes the benchmark (a kit of the
    chapters before the appendix has none: tools/make/bench.mk then builds nothing)."""
    for path in glob.glob(os.path.join(ROOT, 'chapters', '[0-9][0-9]-*.md')):
        with open(path, encoding='utf-8') as f:
            if '\n<<bench/bvhbench.cpp>>=\n' in f.read():
                return True
    return False


def make(*args):
    env = {k: v for k, v in os.environ.items() if k not in MAKE_VARIABLES}
    return subprocess.run(['make', '--no-print-directory'] + list(args),
                          cwd=ROOT, env=env, capture_output=True, text=True)


def default_compiler():
    # make's own default, unless the environment names another
    return os.environ.get('CXX', 'g++')


def write_rays(path, rays):
    with open(path, 'wb') as f:
        for ray in rays:
            f.write(struct.pack('<6f', *ray))


@unittest.skipUnless(has_benchmark(), 'no chapter of this book writes the benchmark')
class BenchProgramTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        build = make('bench-build')
        if build.returncode != 0:
            raise AssertionError('make bench-build failed:\n' + build.stdout +
                                 build.stderr)
        cls.binary = os.path.join(ROOT, 'build', 'float', 'asof',
                                  last_chapter_number(), 'bench', 'bvhbench')

    def run_bench(self, benchmark_filter, json_file=None):
        with tempfile.TemporaryDirectory() as tmp:
            return subprocess.run(
                [self.binary, '--data', os.path.join(tmp, 'none'),
                 '--mesh', 'data/bunny.ply', '--methods', 'sah',
                 '--passes', '1', '--builds', '1',
                 '--json', json_file or os.path.join(tmp, 'out.json'),
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

    def test_default_configuration_is_named_with_the_ratios(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, 'out.json')
            r = self.run_bench('first|final', out)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(out, encoding='utf-8') as f:
                data = json.load(f)
        self.assertEqual((data['cxx'], data['cxxflags']), (default_compiler(), '-O2'))
        self.assertIn('built with %s -O2 (%s)' % (data['cxx'], data['compiler']),
                      r.stdout)
        # The JSON's ratios are the ones the table prints, to its two digits:
        # for the camera rays, the incoherent rays and the build.
        printed = re.search(r'^SAH .* build [0-9.]+x$', r.stdout, re.M)
        self.assertIsNotNone(printed, r.stdout)
        final, = [x for x in data['results'] if x['version'] == 'final']
        first, = [x for x in data['results'] if x['version'] == 'first']
        rays = list(final['rays'])  # in the order of the ray sets
        self.assertEqual(['%.2f' % final['rays'][k]['ratio'] for k in rays] +
                         ['%.2f' % final['build_ratio']],
                         re.findall(r' ([0-9.]+)x', printed.group(0)))
        self.assertEqual([first['rays'][k]['ratio'] for k in rays], [1, 1])
        # bunny.ply has no reference hit counts: no record claims a check.
        self.assertFalse(any('reference' in v for x in data['results']
                             for v in x['rays'].values()))


@unittest.skipUnless(has_benchmark(), 'no chapter of this book writes the benchmark')
class BenchConfigurationTest(unittest.TestCase):
    """A configuration other than the default, built into a scratch BUILD:
    -O0, because it compiles fastest, and a macro whose '=' the directory's
    name must replace."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.build_dir = os.path.join(cls.tmp.name, 'build')
        # V=1: the commands in full, which the tests read.
        cls.build = make('bench-build', 'V=1', 'BUILD=' + cls.build_dir,
                         'BENCH_CXXFLAGS=-O0 -DLRT_UNUSED_MACRO=1')
        if cls.build.returncode != 0:
            raise AssertionError('make bench-build failed:\n' + cls.build.stdout +
                                 cls.build.stderr)
        cls.config_dir = os.path.join(cls.build_dir, 'bench',
                                      default_compiler() + '_-O0_-DLRT_UNUSED_MACRO_1')

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_library_and_program_are_built_with_the_flags_in_their_directory(self):
        commands = self.build.stdout.replace('\\\n', ' ')
        compiles = [line for line in commands.splitlines()
                    if re.search(r' -c \S+\.cpp ', line) or 'bvhbench.cpp' in line]
        library = [c for c in compiles if '/lrt/' in c]
        self.assertGreater(len(library), 5, self.build.stdout)
        self.assertEqual(len(compiles) - len(library), 1, self.build.stdout)
        for c in compiles:
            # The library compiles as `cd DIR && CCACHE_NOHASHDIR=1 [ccache] CXX ...`.
            command = re.sub(r'^cd \S+ && (\w+=\S* )*(\S*/ccache )?', '', c)
            self.assertTrue(command.startswith(default_compiler() + ' '), c)
            self.assertIn(' -O0 -DLRT_UNUSED_MACRO=1 ', c)
            self.assertIn(self.config_dir, c)
        self.assertTrue(os.path.isfile(os.path.join(
            self.config_dir, 'float', 'asof', last_chapter_number(), 'liblrt.a')))

    def test_configuration_is_named_in_table_and_json(self):
        binary = os.path.join(self.config_dir, 'float', 'asof',
                              last_chapter_number(), 'bench', 'bvhbench')
        out = os.path.join(self.tmp.name, 'out.json')
        rays = os.path.join(self.tmp.name, 'rays.bin')
        # a few rays through the bunny's bounds, and a few that miss them
        write_rays(rays, [(-0.2 + 0.01 * i, 0.1, 1, 0, 0, -1) for i in range(40)] +
                   [(5, 5, 5, 0, 0, 1)] * 4)
        r = subprocess.run([binary, '--mesh', 'data/bunny.ply', '--rays', rays,
                            '--methods', 'sah', '--passes', '1', '--builds', '1',
                            '--json', out, '--benchmark_color=false'],
                           cwd=ROOT, capture_output=True, text=True, timeout=300)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out, encoding='utf-8') as f:
            data = json.load(f)
        self.assertEqual(data['cxx'], default_compiler())
        self.assertEqual(data['cxxflags'], '-O0 -DLRT_UNUSED_MACRO=1')
        self.assertRegex(data['compiler'], r'^(GCC|Clang) [0-9]+\.[0-9]')
        self.assertIn('built with %s -O0 -DLRT_UNUSED_MACRO=1 (%s)'
                      % (data['cxx'], data['compiler']), r.stdout)

    def test_unknown_compiler_is_a_clear_error(self):
        r = make('bench-build', 'BUILD=' + self.build_dir,
                 'BENCH_CXX=no-such-compiler++')
        self.assertNotEqual(r.returncode, 0)
        self.assertIn('make bench: BENCH_CXX=no-such-compiler++: no such compiler',
                      r.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.build_dir, 'bench',
                                                     'no-such-compiler++_-O2')))


class BenchTableTest(unittest.TestCase):
    """tools/bench/table.py --configurations: one row per JSON file."""

    @staticmethod
    def record(version, mesh, triangles, speeds, ratios):
        return {'mesh': mesh, 'triangles': triangles, 'method': 'SAH',
                'version': version, 'build_ms': 10.0, 'build_ratio': 0.5,
                'rays': {name: {'mrays_per_s': s, 'hits': 1, 'sum_t': 1.0,
                                'ratio': q}
                         for name, s, q in zip(('rays_primary.bin',
                                                'rays_incoherent.bin'),
                                               speeds, ratios)}}

    def run_table(self, files):
        with tempfile.TemporaryDirectory() as tmp:
            paths = []
            for i, data in enumerate(files):
                paths.append(os.path.join(tmp, '%d.json' % i))
                with open(paths[-1], 'w', encoding='utf-8') as f:
                    json.dump(data, f)
            return subprocess.run(
                [sys.executable, os.path.join(ROOT, 'tools', 'bench', 'table.py'),
                 '--configurations'] + paths, capture_output=True, text=True)

    def configuration(self, cxx, flags, speed, ratio=2.5, build_ms=10.0):
        results = []
        for mesh, triangles in (('bunny_L4', 940544), ('bunny_L2', 58784)):
            results.append(self.record('first', mesh, triangles, (1, 0.5), (1, 1)))
            results.append(self.record('final', mesh, triangles,
                                       (speed, speed / 4), (ratio, 4.25)))
            results[-1]['build_ms'] = build_ms
        return {'cxx': cxx, 'cxxflags': flags, 'compiler': 'GCC 12.2.0',
                'results': results}

    def test_one_row_per_configuration_meshes_by_size(self):
        r = self.run_table([self.configuration('g++', '-O2', 10.9),
                            self.configuration('clang++', '-O3 -march=native', 7.51)])
        self.assertEqual(r.returncode, 0, r.stderr)
        lines = r.stdout.splitlines()
        self.assertEqual(lines[0], '| compiler and flags | 58,784, camera | '
                         '58,784, incoherent | 940,544, camera | '
                         '940,544, incoherent | 58,784, build ms | 940,544, build ms |')
        self.assertEqual(lines[2], '| `g++ -O2` | 10.9 (2.50×) | 2.73 (4.25×) | '
                         '10.9 (2.50×) | 2.73 (4.25×) | 10 | 10 |')
        self.assertTrue(lines[3].startswith('| `clang++ -O3 -march=native` | 7.51 '))
        self.assertEqual(len(lines), 4)

    def test_rounds_of_a_configuration_give_one_row_of_medians(self):
        # Three rounds of g++ -O3 between two of g++ -O2, files interleaved as
        # tools/bench/compare.py writes them; the ratio is the median of the
        # rounds' ratios, not the ratio of the median speeds.
        r = self.run_table([self.configuration('g++', '-O2', 10, 2.0, 12),
                            self.configuration('g++', '-O3', 9, 2.2, 20),
                            self.configuration('g++', '-O2', 12, 3.0, 14),
                            self.configuration('g++', '-O3', 30, 2.4, 18),
                            self.configuration('g++', '-O3', 11, 2.9, 16)])
        self.assertEqual(r.returncode, 0, r.stderr)
        lines = r.stdout.splitlines()
        self.assertEqual(len(lines), 4)
        self.assertEqual(lines[2], '| `g++ -O2` | 11 (2.50×) | 2.75 (4.25×) | '
                         '11 (2.50×) | 2.75 (4.25×) | 13 | 13 |')
        self.assertEqual(lines[3], '| `g++ -O3` | 11 (2.40×) | 2.75 (4.25×) | '
                         '11 (2.40×) | 2.75 (4.25×) | 18 | 18 |')

    def test_a_hit_count_off_the_reference_is_an_error(self):
        good = self.configuration('g++', '-O3', 10)
        wrong = self.configuration('g++', '-O3', 10)
        rays = wrong['results'][3]['rays']['rays_primary.bin']
        rays['hits'], rays['reference'] = 398700, 'MISMATCH'
        r = self.run_table([good, wrong])
        self.assertNotEqual(r.returncode, 0)
        self.assertIn('1.json: 58784 triangles: rays_primary.bin: 398700 hits, not the '
                      'reference count', r.stderr)

    def test_a_file_without_the_configuration_is_an_error(self):
        old = self.configuration('g++', '-O2', 10)
        del old['cxx']
        r = self.run_table([self.configuration('g++', '-O3', 10), old])
        self.assertNotEqual(r.returncode, 0)
        self.assertIn('1.json: the compiler and flags are not recorded', r.stderr)

    def test_a_missing_ratio_is_an_error(self):
        c = self.configuration('g++', '-O3', 10)
        del c['results'][1]['rays']['rays_incoherent.bin']['ratio']
        r = self.run_table([c])
        self.assertNotEqual(r.returncode, 0)
        self.assertIn('0.json: 940544 triangles: no rays_incoherent.bin', r.stderr)


class BenchScriptsTest(unittest.TestCase):
    """The scripts that run make find the repository from where they lie
    (tools/bench/): moved one folder down, they ran make in tools/."""

    def test_the_scripts_run_make_in_the_repository(self):
        sys.path.insert(0, ROOT)
        from tools.bench import compare, loop
        self.assertEqual(compare.ROOT, ROOT)
        self.assertEqual(loop.ROOT, ROOT)
        self.assertTrue(os.path.exists(os.path.join(loop.ROOT, 'Makefile')))


if __name__ == '__main__':
    unittest.main()
