"""Tests of the benchmark of Appendix A, bench/bvhbench.cpp and its make rules
(tools/make/bench.mk), as a user runs them: options that select only part of the
benchmarks must give a clear message, never a crash; a configuration of
compiler and flags builds the library and the program with them, in a
directory of its own, and is named in the table and the JSON; an unknown
compiler is a clear error; tools/bench/table.py turns the JSON of several
configurations into one table. With BENCH_PEERS=embree the program measures
Embree beside lrt: it runs, agrees with lrt and with a brute-force count of
the hits, rotates the order of the versions in each round, and stops with a
clear message when the peer disagrees (a program built with an injected
fault); an unknown peer is a clear error.

The program is built with `make bench-build` (the same rule `make` uses), in
the default configuration: the make that runs these tests may carry
SANITIZE=1 or FLOAT=double, which the benchmark is not built for, so its
variables are kept out of the inner make. The program makes its own data
from data/bunny.ply (3,674 triangles); nothing here measures time.
"""
import glob
import json
import math
import os
import random
import re
import struct
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
MAKE_VARIABLES = ('MAKEFLAGS', 'MFLAGS', 'MAKELEVEL', 'MAKEOVERRIDES', 'SANITIZE',
                  'FLOAT', 'BUILD', 'CH', 'UPTO', 'BENCH_CXX', 'BENCH_CXXFLAGS',
                  'BENCH_PEERS', 'BENCH_PEER_DEFINES', 'BENCH_EMBREE_BIN')


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
        printed = re.search(r'^SAH .* build [0-9.]+x \[[0-9., ]+\]$', r.stdout, re.M)
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


def read_ply_triangles(path):
    """The triangles of a binary little-endian PLY file of float vertices and
    uchar-counted int indices (data/bunny.ply), as triples of points."""
    with open(path, 'rb') as f:
        data = f.read()
    end = data.index(b'end_header\n') + len(b'end_header\n')
    header = data[:end].decode('ascii').split('\n')
    counts = {line.split()[1]: int(line.split()[2])
              for line in header if line.startswith('element ')}
    assert 'format binary_little_endian 1.0' in header, header
    nv, nf = counts['vertex'], counts['face']
    v = struct.unpack_from('<%df' % (3 * nv), data, end)
    points = [v[3 * i:3 * i + 3] for i in range(nv)]
    triangles, offset = [], end + 12 * nv
    for _ in range(nf):
        n, = struct.unpack_from('<B', data, offset)
        assert n == 3
        a, b, c = struct.unpack_from('<3i', data, offset + 1)
        offset += 13
        triangles.append((points[a], points[b], points[c]))
    return points, triangles


def brute_force_hits(triangles, rays):
    """The closest hit of each ray among all the triangles, in double
    precision (Moller-Trumbore), or None: an oracle that shares nothing with
    lrt's watertight test or Embree's."""
    pre = []
    for p0, p1, p2 in triangles:
        e1 = [p1[k] - p0[k] for k in range(3)]
        e2 = [p2[k] - p0[k] for k in range(3)]
        pre.append((p0, e1, e2))
    result = []
    for ox, oy, oz, dx, dy, dz in rays:
        best = None
        for p0, e1, e2 in pre:
            px, py, pz = dy * e2[2] - dz * e2[1], dz * e2[0] - dx * e2[2], dx * e2[1] - dy * e2[0]
            det = e1[0] * px + e1[1] * py + e1[2] * pz
            if det == 0:
                continue
            inv = 1 / det
            sx, sy, sz = ox - p0[0], oy - p0[1], oz - p0[2]
            u = (sx * px + sy * py + sz * pz) * inv
            if u < 0 or u > 1:
                continue
            qx, qy, qz = sy * e1[2] - sz * e1[1], sz * e1[0] - sx * e1[2], sx * e1[1] - sy * e1[0]
            v = (dx * qx + dy * qy + dz * qz) * inv
            if v < 0 or u + v > 1:
                continue
            t = (e2[0] * qx + e2[1] * qy + e2[2] * qz) * inv
            if t > 0 and (best is None or t < best):
                best = t
        result.append(best)
    return result


@unittest.skipUnless(has_benchmark(), 'no chapter of this book writes the benchmark')
class BenchEmbreeTest(unittest.TestCase):
    """make bench BENCH_PEERS=embree's program on data/bunny.ply with a small
    ray file. Embree must be installed (tools/deps.sh embree; CI installs it):
    without it the build fails and so do these tests, never skipped."""
    RAYS = 600
    FAULT = 10  # the faulty program drops the hit of every 10th ray

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        build = make('bench-embree-build', 'BENCH_PEERS=embree')
        if build.returncode != 0:
            raise AssertionError('make bench-embree-build BENCH_PEERS=embree failed '
                                 '(is libembree-dev installed? tools/deps.sh embree):\n' +
                                 build.stdout + build.stderr)
        cls.binary = os.path.join(ROOT, 'build', 'float', 'asof',
                                  last_chapter_number(), 'bench', 'bvhbench-embree')
        cls.faulty = os.path.join(cls.tmp.name, 'bvhbench-fault')
        build = make('bench-embree-build', 'BENCH_PEERS=embree',
                     'BENCH_PEER_DEFINES=-DLRT_BENCH_EMBREE_FAULT=%d' % cls.FAULT,
                     'BENCH_EMBREE_BIN=' + cls.faulty)
        if build.returncode != 0:
            raise AssertionError('the faulty program did not build:\n' +
                                 build.stdout + build.stderr)
        # Rays from random points of a sphere around the bunny toward random
        # points of its box, like the incoherent rays of the standard data.
        cls.points, cls.triangles = read_ply_triangles(os.path.join(ROOT, 'data', 'bunny.ply'))
        lo = [min(p[k] for p in cls.points) for k in range(3)]
        hi = [max(p[k] for p in cls.points) for k in range(3)]
        center = [(lo[k] + hi[k]) / 2 for k in range(3)]
        radius = 1.5 * 0.5 * sum((hi[k] - lo[k]) ** 2 for k in range(3)) ** 0.5
        rng = random.Random(43)
        cls.rays = []
        for _ in range(cls.RAYS):
            z, phi = 1 - 2 * rng.random(), 2 * math.pi * rng.random()
            s = math.sqrt(1 - z * z)
            o = (center[0] + radius * s * math.cos(phi), center[1] + radius * s * math.sin(phi),
                 center[2] + radius * z)
            target = [lo[k] + (hi[k] - lo[k]) * rng.random() for k in range(3)]
            d = [target[k] - o[k] for k in range(3)]
            n = math.sqrt(sum(x * x for x in d))
            # rounded to float, as the file stores them and both sides read them
            ray = struct.unpack('<6f', struct.pack('<6f', *o, *(x / n for x in d)))
            cls.rays.append(ray)
        cls.ray_file = os.path.join(cls.tmp.name, 'rays.bin')
        write_rays(cls.ray_file, cls.rays)
        cls.oracle = brute_force_hits(cls.triangles, cls.rays)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def run_bench(self, binary, passes=1):
        out = os.path.join(self.tmp.name, 'out.json')
        if os.path.exists(out):
            os.remove(out)
        r = subprocess.run([binary, '--mesh', 'data/bunny.ply', '--rays', self.ray_file,
                            '--methods', 'sah,middle', '--passes', str(passes),
                            '--builds', '1', '--json', out, '--benchmark_color=false'],
                           cwd=ROOT, capture_output=True, text=True, timeout=300)
        data = None
        if os.path.exists(out):
            with open(out, encoding='utf-8') as f:
                data = json.load(f)
        return r, data

    def test_embree_runs_beside_lrt_agrees_and_prints_the_ratio(self):
        r, data = self.run_bench(self.binary)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertNotIn('ERROR OCCURRED', r.stdout)
        # the oracle: a brute-force count of the hits in double precision
        oracle = self.oracle
        hits = sum(t is not None for t in oracle)
        self.assertGreater(hits, self.RAYS // 4)
        self.assertLess(hits, self.RAYS)
        agreement, = data['agreement']
        self.assertEqual((agreement['mesh'], agreement['rays'], agreement['count']),
                         ('bunny', 'rays.bin', self.RAYS))
        self.assertLessEqual(agreement['differ'], 1)
        for side in ('lrt_hits', 'peer_hits'):
            self.assertLessEqual(abs(agreement[side] - hits), 1, (side, hits))
        self.assertIn('lrt and embree on rays.bin: %d rays, %d and %d hits, %d differ'
                      % (self.RAYS, agreement['lrt_hits'], agreement['peer_hits'],
                         agreement['differ']), r.stdout)
        records = {(x['method'], x['version']): x for x in data['results']}
        # the peer is measured in the SAH's group only, with no tree statistics
        self.assertIn(('SAH', 'embree'), records)
        self.assertNotIn(('Middle', 'embree'), records)
        self.assertNotIn('nodes', records['SAH', 'embree'])
        embree, final = records['SAH', 'embree'], records['SAH', 'final']
        oracle_sum = sum(t for t in oracle if t is not None)
        for record in (embree, final):
            self.assertLessEqual(abs(record['rays']['rays.bin']['hits'] - hits), 1)
            self.assertAlmostEqual(record['rays']['rays.bin']['sum_t'] / oracle_sum, 1,
                                   delta=1e-3)
        # one round: the ratio is that of the two throughputs, and its spread nil
        ratio = final['rays']['rays.bin']['versus']['embree']
        self.assertAlmostEqual(ratio['median'], final['rays']['rays.bin']['mrays_per_s'] /
                               embree['rays']['rays.bin']['mrays_per_s'], places=6)
        self.assertEqual(ratio['min'], ratio['max'])
        self.assertIn('embree', final['build_versus'])
        printed = re.search(r'^final / embree: .*\nSAH +rays.bin ([0-9.]+)x '
                            r'\[([0-9.]+), ([0-9.]+)\] build [0-9.]+x \[', r.stdout, re.M)
        self.assertIsNotNone(printed, r.stdout)
        self.assertEqual(printed.group(1), '%.2f' % ratio['median'])
        self.assertTrue(re.search(r'^SAH +embree +[0-9.]+ +- +- +- +- +-$', r.stdout, re.M),
                        r.stdout)

    def test_the_order_of_the_passes_rotates_from_round_to_round(self):
        r, _ = self.run_bench(self.binary, passes=5)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        # Google Benchmark colours its lines even when told not to
        stdout = re.sub(r'\x1b\[[0-9;]*m', '', r.stdout)
        for method, versions in (('SAH', ['first', 'adopted', 'final', 'embree']),
                                 ('Middle', ['first', 'adopted', 'final'])):
            runs = re.findall(r'^bunny/%s/(\w+)/rays\.bin/round:(\d+)' % method, stdout, re.M)
            self.assertEqual(len(runs), 5 * len(versions), stdout)
            n = len(versions)
            for k, (version, round_) in enumerate(runs):
                rnd = int(round_) - 1
                self.assertEqual(rnd, k // n)
                self.assertEqual(version, versions[(rnd + k % n) % n], runs)
            builds = re.findall(r'^bunny/%s/(\w+)/build/round:1' % method, stdout, re.M)
            self.assertEqual(builds, versions)

    def test_a_disagreement_stops_the_run_before_the_passes(self):
        r, data = self.run_bench(self.faulty)
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertIsNone(data)
        message = re.search(r'^bvhbench: lrt and embree disagree on bunny with rays\.bin: '
                            r'(\d+) of %d rays differ \(at most 1 may\), with (\d+) and (\d+) '
                            r'hits; the first is ray (\d+): lrt finds a hit at t = [0-9.]+, '
                            r'embree a miss$' % self.RAYS, r.stderr, re.M)
        self.assertIsNotNone(message, r.stderr)
        differ, lrt, peer, first = map(int, message.groups())
        oracle = self.oracle
        dropped = [i for i in range(0, self.RAYS, self.FAULT) if oracle[i] is not None]
        self.assertGreater(len(dropped), 2)
        self.assertLessEqual(abs(differ - len(dropped)), 1)
        self.assertLessEqual(abs(lrt - peer - len(dropped)), 1)
        self.assertEqual(first, dropped[0])
        self.assertNotIn('rays.bin/round:', r.stdout)  # no pass was timed

    def test_unknown_peer_is_a_clear_error(self):
        r = make('bench', 'BENCH_PEERS=embree optix')
        self.assertNotEqual(r.returncode, 0)
        self.assertIn('make bench: BENCH_PEERS=embree optix: unknown peer optix '
                      '(known: embree)', r.stderr)
        self.assertNotIn('CXX', r.stdout)  # stopped before building anything


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
