"""Tests of the measured numbers the book prints (tools/bench/book_numbers.py
and tools/book/measured.lua): each is formatted from the one data file, a
derived number is computed from the values it derives from, a name the data
lacks is an error naming the chapter's file and line, and the weave prints
the values in place of the spans that name them."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, ROOT)

from tools.bench import book_numbers  # noqa: E402

MEASURED_LUA = os.path.join(ROOT, 'tools', 'book', 'measured.lua')


def result(mesh, method, version, build, camera, incoherent, nodes=100):
    rays = {'rays_primary.bin': camera, 'rays_incoherent.bin': incoherent}
    return {'mesh': mesh, 'triangles': 58784, 'method': method, 'version': version,
            'build_ms': build, 'nodes': nodes, 'leaves': 60, 'leaf_size': 4.4861,
            'sah_cost': 20.97, 'depth': 9,
            'rays': {name: {'mrays_per_s': speed, 'ratio': ratio, 'hits': 398701}
                     for name, (speed, ratio) in rays.items()}}


def data():
    counts = {'instructions': 4608.2, 'mispredicted_branches': 51.26, 'cache_misses': 16.87}
    return {
        'setup': {'processor': 'Some CPU', 'compiler': 'GCC 12.2.0', 'cxx': 'g++',
                  'cxxflags': '-O2', 'float': 'float', 'passes': 3,
                  'build_repetitions': 3,
                  'rays': {'rays_primary.bin': 1048576, 'rays_incoherent.bin': 1048576}},
        'results': [
            result('bunny_L2', 'SAH', 'first', 37.7, (4.57, 1.0), (0.6089, 1.0), nodes=600),
            result('bunny_L2', 'SAH', 'adopted', 13.5, (10.53, 2.32), (1.93, 3.19)),
            result('bunny_L2', 'SAH', 'final', 20.0, (12.92, 2.83), (2.48, 4.07), nodes=200),
        ],
        'counts': {'mesh': 'bunny_L2', 'method': 'SAH', 'rays': 65536,
                   'camera_rows': [480, 544], 'cache': '1048576,16,64',
                   'camera': {v: dict(counts) for v in ('first', 'adopted', 'final')},
                   'incoherent': {'first': dict(counts), 'adopted': dict(counts),
                                  'final': dict(counts, instructions=1152.05)}},
        'compilers': [
            {'name': 'gcc-O2', 'cxx': 'g++', 'cxxflags': '-O2', 'compiler': 'GCC 12.2.0',
             'rounds': 3,
             'meshes': {'bunny_L2': {
                 'build_ms': [10.0, 12.0, 11.0],
                 'rays_primary.bin': {'mrays_per_s': [10.0, 8.0, 12.0],
                                      'ratio': [2.7, 2.6, 2.8]},
                 'rays_incoherent.bin': {'mrays_per_s': [2.0, 2.2, 2.4],
                                         'ratio': [4.3, 4.3, 4.3]}}},
             'instructions': {'camera': 1363.0, 'incoherent': 1427.0}},
            {'name': 'gcc-O3', 'cxx': 'g++', 'cxxflags': '-O3', 'compiler': 'GCC 12.2.0',
             'rounds': 3,
             'meshes': {'bunny_L2': {
                 # Round 2 was slow for both: compared round by round, -O3 is
                 # 1.1, 1.1 and 1.0 times as fast; the ratio of the medians
                 # would say 1.15.
                 'build_ms': [12.34, 14.0, 11.0],
                 'rays_primary.bin': {'mrays_per_s': [11.0, 8.8, 12.0],
                                      'ratio': [2.364, 2.1, 2.5]},
                 'rays_incoherent.bin': {'mrays_per_s': [2.587, 2.2, 2.4],
                                         'ratio': [4.26, 4.1, 4.4]}}},
             'instructions': {'camera': 1303.4, 'incoherent': 1371.2}}],
    }


class FormatTest(unittest.TestCase):
    def test_three_significant_digits_with_separators(self):
        cases = {0.6089: '0.609', 12.92: '12.9', 1096.4: '1,096', 9.996: '10.0',
                 2.5: '2.50', 0.0996: '0.0996', 150.4: '150', 99.96: '100'}
        for x, text in cases.items():
            self.assertEqual(book_numbers.significant(x), text, x)

    def test_values_and_derived_values(self):
        v = book_numbers.values(data())
        self.assertEqual(v['L2.triangles'], '58,784')
        self.assertEqual(v['L2.sah.first.incoherent'], '0.609')
        self.assertEqual(v['L2.sah.final.camera.ratio'], '2.83')
        self.assertEqual(v['L2.sah.first.incoherent.us'], '1.6')   # 1 / 0.6089
        # 2.83 / 2.32 and 4.07 / 3.19: the final version's gain over the adopted
        self.assertEqual(v['L2.sah.final.camera.gain'], '22')
        self.assertEqual(v['L2.sah.final.incoherent.gain'], '28')
        self.assertEqual(v['L2.sah.final.build.percent'], '53')   # 20.0 / 37.7
        self.assertEqual(v['L2.sah.first.nodes.perfinal'], '3.0')
        self.assertEqual(v['L2.sah.final.leafsize'], '4.49')
        self.assertEqual(v['count.camera.first.instructions'], '4,608')
        self.assertEqual(v['count.incoherent.first.mispredicted'], '51.3')
        self.assertEqual(v['count.incoherent.first.perfinal'], '4.0')
        self.assertEqual(v['count.rows'], '480 to 543')
        self.assertEqual(v['count.cache'], '1\u00a0MB')
        self.assertEqual(v['setup.rays.camera'], '1,048,576')
        self.assertEqual(v['setup.compiler'], 'GCC\u00a012.2.0')
        self.assertEqual(v['compilers.gcc-O3.L2.camera'], '11.0')
        self.assertEqual(v['compilers.gcc-O3.L2.camera.vs'], '1.10')
        self.assertEqual(v['compilers.gcc-O2.L2.camera.vs'], '1.00')
        self.assertEqual(v['compilers.gcc-O3.L2.incoherent.ratio'], '4.26')
        self.assertEqual(v['compilers.gcc-O3.L2.build'], '12.3')
        self.assertEqual(v['compilers.gcc-O3.L2.build.vs'], '1.17')   # 14 / 12
        self.assertEqual(v['compilers.gcc-O3.instructions.incoherent'], '1,371')

    def test_the_peer_s_values(self):
        d = data()
        peer = {'instructions': 756.0, 'mispredicted_branches': 6.03, 'cache_misses': 0.4}
        for rays in ('camera', 'incoherent'):
            d['counts'][rays]['embree'] = dict(peer)
        # Embree reports no tree: its record has speeds and a build time only.
        d['results'].append({
            'mesh': 'bunny_L2', 'triangles': 58784, 'method': 'SAH', 'version': 'embree',
            'build_ms': 18.23, 'rays': {
                name: {'mrays_per_s': speed, 'ratio': 2.9, 'hits': 398701}
                for name, speed in (('rays_primary.bin', 12.81),
                                    ('rays_incoherent.bin', 5.096))}})
        final = d['results'][2]
        final['build_versus'] = {'embree': {'median': 0.7219, 'min': 0.634, 'max': 0.8412}}
        final['rays']['rays_primary.bin']['versus'] = {
            'first': {'median': 2.83, 'min': 2.6, 'max': 2.9},
            'embree': {'median': 0.9549, 'min': 0.915, 'max': 1.004}}
        d['agreement'] = [
            {'mesh': mesh, 'rays': rays, 'count': 1048576, 'lrt_hits': 398701,
             'peer_hits': 398701, 'differ': differ}
            for mesh, rays, differ in (('bunny_L0', 'rays_primary.bin', 0),
                                       ('bunny_L2', 'rays_primary.bin', 4),
                                       ('bunny_L2', 'rays_incoherent.bin', 2),
                                       ('bunny_L4', 'rays_primary.bin', 12),
                                       ('bunny_L4', 'rays_incoherent.bin', 8))]
        d['setup']['embree'] = '3.13.5'
        v = book_numbers.values(d)
        self.assertEqual(v['L2.sah.embree.camera'], '12.8')
        self.assertEqual(v['L2.sah.embree.incoherent'], '5.10')
        self.assertEqual(v['L2.sah.embree.build'], '18.2')
        self.assertEqual(v['L2.sah.final.camera.vsembree'], '0.95')
        self.assertEqual(v['L2.sah.final.camera.vsembree.min'], '0.92')
        self.assertEqual(v['L2.sah.final.camera.vsembree.max'], '1.00')
        self.assertEqual(v['L2.sah.final.build.vsembree'], '0.72')
        self.assertNotIn('L2.sah.final.incoherent.vsembree', v)   # not measured
        self.assertNotIn('L2.sah.embree.nodes', v)
        # 4,608 and 1,152 instructions per ray against Embree's 756
        self.assertEqual(v['count.camera.final.perembree'], '6.1')
        self.assertEqual(v['count.incoherent.final.perembree'], '1.5')
        self.assertEqual(v['count.camera.embree.mispredicted'], '6.0')
        self.assertEqual(v['L2.agree.camera'], '4')
        # The standard data's meshes only: L0's 0 is not the least
        self.assertEqual(v['agree.least'], '2')
        self.assertEqual(v['agree.most'], '12')
        self.assertEqual(v['setup.embree'], '3.13.5')

    def test_data_that_is_not_the_measurements_is_an_error(self):
        broken = data()
        del broken['counts']['camera']
        with self.assertRaises(SystemExit) as e:
            book_numbers.values(broken, 'x.json')
        self.assertIn('x.json', str(e.exception.code))


class CheckTest(unittest.TestCase):
    def test_an_unknown_name_is_reported_with_file_and_line(self):
        with tempfile.TemporaryDirectory() as tmp:
            chapter = os.path.join(tmp, '07-x.md')
            with open(chapter, 'w', encoding='utf-8') as f:
                f.write('Rays at [L2.sah.final.camera]{.m} per second,\n'
                        'and at [L2.sah.final.camra]{.m}.\n')
            errors = book_numbers.check(book_numbers.values(data()), [chapter])
        self.assertEqual(errors, ["%s:2: no measured number named 'L2.sah.final.camra'"
                                  % chapter])

    def run_check(self, chapter_text, data_file):
        with tempfile.TemporaryDirectory() as tmp:
            chapter = os.path.join(tmp, '07-x.md')
            with open(chapter, 'w', encoding='utf-8') as f:
                f.write(chapter_text)
            return subprocess.run([sys.executable, os.path.join(ROOT, 'tools', 'bench',
                                                                'book_numbers.py'),
                                   '--check', data_file or os.path.join(tmp, 'none.json'),
                                   chapter], capture_output=True, text=True), chapter

    def test_a_book_without_measured_numbers_needs_no_data(self):
        r, _ = self.run_check('No numbers here.\n', None)
        self.assertEqual(r.returncode, 0, r.stderr)

    def test_a_measured_number_without_the_data_is_an_error_at_its_line(self):
        r, chapter = self.run_check('Text.\nAt [L2.sah.final.camera]{.m}.\n', None)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn(chapter + ':2:', r.stderr)

    def test_the_book_names_only_numbers_that_its_data_has(self):
        chapters = sorted(os.path.join(ROOT, 'chapters', f)
                          for f in os.listdir(os.path.join(ROOT, 'chapters')))
        table = book_numbers.load(os.path.join(ROOT, 'figures', 'data',
                                               'bvh-measurements.json'))
        self.assertEqual(book_numbers.check(table, chapters), [])


class WeaveTest(unittest.TestCase):
    def weave(self, text, measurements=True):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, 'm.json')
            with open(path, 'w', encoding='utf-8') as f:
                json.dump(data(), f)
            meta = '---\nmeasurements: %s\n---\n\n' % path if measurements else ''
            return subprocess.run(['pandoc', '--from', 'markdown', '--to', 'plain',
                                   '--lua-filter', MEASURED_LUA],
                                  input=meta + text, capture_output=True, text=True)

    def test_a_span_prints_its_value(self):
        r = self.weave('| a | b |\n|---|---|\n| [L2.sah.final.camera]{.m} | '
                       '[count.rows]{.m} |\n\nAt [L2.sah.first.incoherent]{.m} Mrays/s.\n')
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn('12.9', r.stdout)
        self.assertIn('480 to 543', r.stdout)
        self.assertIn('At 0.609 Mrays/s.', r.stdout)
        self.assertNotIn('L2.sah', r.stdout)

    def test_other_spans_are_left_alone(self):
        r = self.weave('A [word]{.smallcaps} stays.\n')
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn('WORD', r.stdout.upper())

    def test_an_unknown_name_stops_the_weave(self):
        r = self.weave('At [L2.sah.final.camra]{.m}.\n')
        self.assertNotEqual(r.returncode, 0)
        self.assertIn('L2.sah.final.camra', r.stderr)

    def test_a_span_without_the_data_file_stops_the_weave(self):
        r = self.weave('At [L2.sah.final.camera]{.m}.\n', measurements=False)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn('measurements', r.stderr)


if __name__ == '__main__':
    unittest.main()
