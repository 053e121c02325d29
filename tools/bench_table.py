#!/usr/bin/env python3
"""Turn the JSON of `make bench` into tables.

    tools/bench_table.py figures/data/bvhbench-levels.json > figures/bvh-bench.dat
    tools/bench_table.py --configurations build/bvhbench.json \\
        build/bench/g++_-O3/bvhbench.json ... > table.md

The first form writes a whitespace-separated table for a plot: one row per
mesh (sorted by triangle count) with, for the SAH trees of the first and the
final version, build time in ms and Mrays/s for the camera rays and for the
incoherent rays. Its first line names the columns, which the book's plot
(pgfplots, chapter 7) reads by name.

The second compares configurations, one JSON file (one run of `make bench`)
each: a Markdown table with one row per file, named by the compiler command
and flags that the file records, and for each mesh and ray set the final
version's Mrays/s on the SAH tree with its ratio to the first version's (the
median of the rounds' ratios).

Either fails, naming the file, if a value is missing.
"""
import json
import sys

RAYS = ('rays_primary.bin', 'rays_incoherent.bin')
RAY_NAMES = {'rays_primary.bin': 'camera', 'rays_incoherent.bin': 'incoherent'}
VERSIONS = ('first', 'final')


def load(path):
    try:
        with open(path, encoding='utf-8') as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        sys.exit('bench_table: %s: %s' % (path, e))


def sah_results(path, data):
    try:
        results = [r for r in data['results'] if r.get('method') == 'SAH']
    except (KeyError, TypeError) as e:
        sys.exit('bench_table: %s: no results: %s' % (path, e))
    if not results:
        sys.exit('bench_table: %s: no SAH results' % path)
    return results


def plot_table(path):
    rows = {}
    for r in sah_results(path, load(path)):
        if r.get('version') not in VERSIONS:
            continue
        row = rows.setdefault(r['triangles'], {})
        row[r['version'], 'build'] = r['build_ms']
        for rays in RAYS:
            if rays in r['rays']:
                row[r['version'], rays] = r['rays'][rays]['mrays_per_s']
    columns = [(v, k) for v in VERSIONS for k in ('build',) + RAYS]
    print('triangles ' + ' '.join('%s_%s' % (v, k.split('.')[0])
                                  for v, k in columns))
    for triangles in sorted(rows):
        row = rows[triangles]
        missing = [c for c in columns if c not in row]
        if missing:
            sys.exit('bench_table: %s: %d triangles: no %s' % (path, triangles, missing))
        print(triangles, ' '.join('%.6g' % row[c] for c in columns))


def configuration_table(paths):
    rows, meshes = [], None
    for path in paths:
        data = load(path)
        if 'cxx' not in data or 'cxxflags' not in data:
            sys.exit('bench_table: %s: the compiler and flags are not recorded '
                     '(a JSON file of an older make bench?)' % path)
        final = {r['triangles']: r for r in sah_results(path, data)
                 if r.get('version') == 'final'}
        if meshes is None:
            meshes = sorted(final)
        if sorted(final) != meshes:
            sys.exit('bench_table: %s: meshes of %s triangles, where %s has %s'
                     % (path, sorted(final), paths[0], meshes))
        cells = []
        for triangles in meshes:
            for rays in RAYS:
                r = final[triangles]['rays'].get(rays)
                if r is None or 'ratio' not in r:
                    sys.exit('bench_table: %s: %d triangles: no %s with a ratio'
                             % (path, triangles, rays))
                cells.append('%.3g (%.2f×)' % (r['mrays_per_s'], r['ratio']))
        rows.append(['`%s %s`' % (data['cxx'], data['cxxflags'])] + cells)
    header = ['compiler and flags'] + ['%s, %s' % ('{:,}'.format(t), RAY_NAMES[r])
                                       for t in meshes for r in RAYS]
    print('| ' + ' | '.join(header) + ' |')
    print('|---' + '|---:' * (len(header) - 1) + '|')
    for row in rows:
        print('| ' + ' | '.join(row) + ' |')


def main(argv):
    if len(argv) >= 2 and argv[0] == '--configurations':
        configuration_table(argv[1:])
    elif len(argv) == 1 and not argv[0].startswith('--'):
        plot_table(argv[0])
    else:
        sys.exit(__doc__)


if __name__ == '__main__':
    main(sys.argv[1:])
