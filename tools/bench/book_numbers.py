#!/usr/bin/env python3
"""The measured numbers that the book prints, by name, from one data file.

    tools/bench/book_numbers.py --lua MEASUREMENTS.json
    tools/bench/book_numbers.py --list MEASUREMENTS.json
    tools/bench/book_numbers.py --check MEASUREMENTS.json CHAPTER.md...

A chapter writes a measured number as a span, `[L2.sah.final.camera]{.m}`,
and the weave prints in its place the value of that name, formatted as the
book prints numbers (tools/book/measured.lua runs `--lua`, which writes the
values as a Lua table, since pandoc's Lua has no JSON reader). So the text,
its tables and the plot (tools/bench/table.py) all take their numbers from
the one file that tools/bench/measure.py writes, and cannot disagree.

`--list` prints every name and its value; `--check` fails, naming the file and
line, on a span whose name the data does not define (make lint runs it).

The names, for mesh Lk (k = 0..4), method (sah, hlbvh, middle, equalcounts),
version (first, adopted, final; embree, with sah only) and ray set (camera,
incoherent):

    Lk.triangles, Lk.hits.camera            the mesh's size, hit counts
    Lk.method.version.build                 build time, ms
    Lk.method.version.nodes, .leaves, .leafsize, .depth, .sahcost
    Lk.method.version.interior, .binaryinterior   interior nodes, of the
                                            tree and of a binary tree of its leaves
    Lk.method.version.camera                Mrays/s
    Lk.method.version.camera.ratio          speed / the first version's (median of rounds)
    Lk.method.version.camera.us             microseconds per ray
    Lk.sah.final.camera.vsembree            speed / Embree's (median of rounds),
                                            also .min and .max over the rounds;
                                            Lk.sah.final.build.vsembree likewise
    Lk.agree.camera                         rays whose hits lrt and Embree
                                            report differently (Appendix A)
    agree.least, agree.most                 the fewest and the most of those,
                                            over L2 and L4 and both ray sets
    Lk.method.final.camera.gain             percent faster than the adopted version
    Lk.sah.final.build.percent              build time, percent of the first version's
    Lk.sah.first.nodes.perfinal             the first tree's nodes per node of the final one
    count.ray set.version.instructions      per ray (callgrind), also
                                            .mispredicted, .misses
    count.ray set.first.perfinal            the first version's instructions per final one's
    count.ray set.final.perembree           the final version's instructions per Embree's
    count.rays, count.rows, count.cache     the samples and the simulated cache
    compilers.NAME.Lk.camera, .ratio, .build   the final version built by
                                            configuration NAME (gcc-O2, gcc-O3,
                                            gcc-O3-native, clang-O2, clang-O3),
                                            medians over the rounds
    compilers.NAME.Lk.camera.vs, .build.vs  its speed and build time over the
                                            first configuration's, in the same
                                            round (median over the rounds)
    compilers.NAME.instructions.camera      its instructions per ray (callgrind)
    compilers.NAME.compiler, .rounds
    setup.processor, setup.compiler, setup.flags, setup.passes, setup.builds,
    setup.embree (Embree's version), setup.valgrind,
    setup.rays.camera, setup.rays.incoherent   the sizes of the ray sets
"""
import json
import math
import statistics
import os
import re
import sys

RAY_SETS = {'rays_primary.bin': 'camera', 'rays_incoherent.bin': 'incoherent'}
METHODS = {'SAH': 'sah', 'HLBVH': 'hlbvh', 'Middle': 'middle', 'EqualCounts': 'equalcounts'}
SPAN = re.compile(r'\[([A-Za-z0-9_.-]+)\]\{\.m\}')


def fail(message):
    sys.exit('book_numbers: ' + message)


def thousands(n):
    return '{:,}'.format(int(round(n)))


def significant(x, digits=3):
    """x to `digits` significant digits, with thousands separators: 0.609, 12.9, 1,096."""
    if x <= 0:
        fail('cannot print %r as a measurement' % x)
    for _ in range(2):   # once more if rounding reached the next power of ten
        if x >= 10 ** (digits - 1):
            return thousands(x)
        decimals = digits - 1 - math.floor(math.log10(x))
        x = round(x, decimals)
    return '%.*f' % (decimals, x)


def median(values):
    return statistics.median(list(values))


def mesh_key(name, path):
    m = re.fullmatch(r'bunny_L(\d)', name)
    if not m:
        fail('%s: a mesh named %r (bunny_L0 ... bunny_L4 expected)' % (path, name))
    return 'L' + m.group(1)


def versus(out, name, ratios):
    """The final version's ratio to Embree's, with its range over the rounds,
    where the record has it: `ratios` is the JSON's `versus` or `build_versus`
    (absent from the records of the other versions)."""
    embree = (ratios or {}).get('embree')
    if embree:
        for key, suffix in (('median', ''), ('min', '.min'), ('max', '.max')):
            out['%s.vsembree%s' % (name, suffix)] = '%.2f' % embree[key]


def values(data, path='the measurements'):
    """Every printable name -> its text."""
    out = {}
    try:
        setup = data['setup']
        out['setup.processor'] = setup['processor']
        out['setup.compiler'] = setup['compiler'].replace('GCC ', 'GCC\u00a0')
        out['setup.flags'] = setup['cxxflags']
        out['setup.passes'] = str(setup['passes'])
        out['setup.builds'] = str(setup['build_repetitions'])
        by = {}
        for r in data['results']:
            mesh, method = mesh_key(r['mesh'], path), METHODS[r['method']]
            by[mesh, method, r['version']] = r
            out[mesh + '.triangles'] = thousands(r['triangles'])
            base = '%s.%s.%s' % (mesh, method, r['version'])
            out[base + '.build'] = significant(r['build_ms'])
            if r['version'] == 'embree':
                # The peer reports no tree, only its speeds (Appendix A).
                for ray_file, rays in RAY_SETS.items():
                    v = r['rays'][ray_file]
                    out['%s.%s' % (base, rays)] = significant(v['mrays_per_s'])
                    out['%s.%s.ratio' % (base, rays)] = '%.2f' % v['ratio']
                continue
            out[base + '.nodes'] = thousands(r['nodes'])
            out[base + '.leaves'] = thousands(r['leaves'])
            out[base + '.leafsize'] = '%.2f' % r['leaf_size']
            out[base + '.depth'] = str(r['depth'])
            # Interior nodes: the tree's; those of the binary tree that a
            # tree of these leaves collapses (a binary tree of k leaves has k - 1).
            out[base + '.interior'] = thousands(r['nodes'] - r['leaves'])
            out[base + '.binaryinterior'] = thousands(r['leaves'] - 1)
            out[base + '.sahcost'] = significant(r['sah_cost'])
            for ray_file, rays in RAY_SETS.items():
                v = r['rays'][ray_file]
                out['%s.%s' % (base, rays)] = significant(v['mrays_per_s'])
                out['%s.%s.ratio' % (base, rays)] = '%.2f' % v['ratio']
                out['%s.%s.us' % (base, rays)] = significant(1 / v['mrays_per_s'], 2)
                out['%s.hits.%s' % (mesh, rays)] = thousands(v['hits'])
                versus(out, '%s.%s' % (base, rays), v.get('versus'))
            versus(out, base + '.build', r.get('build_versus'))
        for (mesh, method, version), r in by.items():
            if version != 'final' or (mesh, method, 'adopted') not in by:
                continue
            adopted = by[mesh, method, 'adopted']
            first = by[mesh, method, 'first']
            for ray_file, rays in RAY_SETS.items():
                gain = r['rays'][ray_file]['ratio'] / adopted['rays'][ray_file]['ratio']
                out['%s.%s.final.%s.gain' % (mesh, method, rays)] = '%.0f' % (100 * (gain - 1))
            out['%s.%s.final.build.percent' % (mesh, method)] = \
                '%.0f' % (100 * r['build_ms'] / first['build_ms'])
            out['%s.%s.first.nodes.perfinal' % (mesh, method)] = \
                '%.1f' % (first['nodes'] / r['nodes'])
        counts = data['counts']
        out['count.rays'] = thousands(counts['rays'])
        out['count.rows'] = '%d to %d' % (counts['camera_rows'][0], counts['camera_rows'][1] - 1)
        size = int(counts['cache'].split(',')[0])
        out['count.cache'] = '%d\u00a0MB' % (size // 2 ** 20)
        for rays in RAY_SETS.values():
            for version, c in counts[rays].items():
                base = 'count.%s.%s' % (rays, version)
                out[base + '.instructions'] = thousands(c['instructions'])
                out[base + '.mispredicted'] = '%.1f' % c['mispredicted_branches']
                out[base + '.misses'] = '%.1f' % c['cache_misses']
            out['count.%s.first.perfinal' % rays] = '%.1f' % (
                counts[rays]['first']['instructions'] / counts[rays]['final']['instructions'])
            if 'embree' in counts[rays]:
                out['count.%s.final.perembree' % rays] = '%.1f' % (
                    counts[rays]['final']['instructions'] /
                    counts[rays]['embree']['instructions'])
        standard = []   # the standard data's meshes, L2 and L4
        for a in data.get('agreement', []):
            mesh = mesh_key(a['mesh'], path)
            out['%s.agree.%s' % (mesh, RAY_SETS[a['rays']])] = thousands(a['differ'])
            if mesh in ('L2', 'L4'):
                standard.append(a['differ'])
        if standard:
            out['agree.least'] = thousands(min(standard))
            out['agree.most'] = thousands(max(standard))
        for key in ('embree', 'valgrind'):
            if key in setup:
                out['setup.' + key] = setup[key]
        for ray_file, rays in RAY_SETS.items():
            out['setup.rays.' + rays] = thousands(setup['rays'][ray_file])
        compilers = data.get('compilers', [])   # an older file has none
        for c in compilers:
            base = 'compilers.' + c['name']
            out[base + '.compiler'] = c['compiler'].replace(' ', '\u00a0')
            out[base + '.rounds'] = str(c['rounds'])
            for mesh, m in c['meshes'].items():
                # The first configuration, measured in the same rounds, is
                # the one the others are compared with, round by round.
                first = compilers[0]['meshes'][mesh]
                where = '%s.%s' % (base, mesh_key(mesh, path))
                out[where + '.build'] = significant(median(m['build_ms']))
                out[where + '.build.vs'] = '%.2f' % median(
                    a / b for a, b in zip(m['build_ms'], first['build_ms']))
                for ray_file, rays in RAY_SETS.items():
                    speeds = m[ray_file]['mrays_per_s']
                    out['%s.%s' % (where, rays)] = significant(median(speeds))
                    out['%s.%s.ratio' % (where, rays)] = '%.2f' % median(m[ray_file]['ratio'])
                    out['%s.%s.vs' % (where, rays)] = '%.2f' % median(
                        a / b for a, b in zip(speeds, first[ray_file]['mrays_per_s']))
            for rays, n in c.get('instructions', {}).items():
                out['%s.instructions.%s' % (base, rays)] = thousands(n)
    except (KeyError, TypeError, IndexError, ValueError, ZeroDivisionError) as e:
        fail('%s: not the data of tools/bench/measure.py: %s %s' % (path, type(e).__name__, e))
    return out


def load(path):
    try:
        with open(path, encoding='utf-8') as f:
            return values(json.load(f), path)
    except (OSError, ValueError) as e:
        fail('%s: %s' % (path, e))


def lua_string(text):
    """A Lua string literal: printable ASCII as it is, every other byte as \\ddd."""
    return '"' + ''.join(chr(b) if 32 <= b < 127 and b not in (34, 92) else '\\%03d' % b
                         for b in text.encode('utf-8')) + '"'


def lua(table):
    lines = ['return {']
    for name in sorted(table):
        lines.append('  [%s] = %s,' % (lua_string(name), lua_string(table[name])))
    lines.append('}')
    return '\n'.join(lines)


def spans(chapters):
    """(file, line, name) of every measured number the chapters name."""
    found = []
    for chapter in chapters:
        with open(chapter, encoding='utf-8') as f:
            for number, line in enumerate(f, 1):
                found += [(chapter, number, m.group(1)) for m in SPAN.finditer(line)]
    return found


def check(table, chapters):
    return ['%s:%d: no measured number named %r' % (chapter, line, name)
            for chapter, line, name in spans(chapters) if name not in table]


def main(argv):
    if len(argv) >= 2 and argv[0] == '--check':
        named = spans(argv[2:])
        # A book without measured numbers (a kit of early chapters) needs no data.
        if named and not os.path.exists(argv[1]):
            chapter, line, name = named[0]
            sys.exit('%s:%d: names the measured number %r, but there is no %s'
                     % (chapter, line, name, argv[1] or 'measurements file named in '
                        'the book\'s metadata (measurements:)'))
        errors = check(load(argv[1]), argv[2:]) if named else []
        if errors:
            sys.exit('\n'.join(errors))
        return
    if len(argv) >= 2 and argv[0] in ('--lua', '--list'):
        table = load(argv[1])
        if argv[0] == '--lua' and len(argv) == 2:
            print(lua(table))
            return
        if argv[0] == '--list' and len(argv) == 2:
            for name in sorted(table):
                print('%s\t%s' % (name, table[name]))
            return
    sys.exit(__doc__)


if __name__ == '__main__':
    main(sys.argv[1:])
