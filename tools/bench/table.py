#!/usr/bin/env python3
"""Turn the JSON of `make bench` into tables.

    tools/bench/table.py figures/data/bvh-measurements.json > figures/bvh-bench.dat
    tools/bench/table.py --configurations build/bvhbench.json \\
        build/bench/g++_-O3/bvhbench.json ... > table.md

The first form writes a whitespace-separated table for a plot: one row per
mesh (sorted by triangle count) with, for the SAH trees of the first and the
final version, build time in ms and Mrays/s for the camera rays and for the
incoherent rays. Its first line names the columns, which the book's plot
(pgfplots, chapter 7) reads by name.

The second compares configurations: a Markdown table with one row per
configuration, named by the compiler command and flags that its files
record, and for each mesh and ray set the final version's Mrays/s on the SAH
tree with its ratio to the first version's, then the final version's build
time per mesh. A configuration may come as one file (one run of `make
bench`, whose ratios are the medians of its rounds) or as several runs of
the same program (tools/bench/compare.py's rounds): the row then gives the
medians over the files, of the ratios as of the speeds, so that each ratio
pairs runs made side by side.

Either fails, naming the file, if a value is missing, and the second if a
ray set's hits did not match the reference counts.
"""
import json
import statistics
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


def configuration_rounds(path, data):
    """One run of a configuration: {triangles: (build ms, {rays: (Mrays/s,
    ratio)})} for the final version's SAH trees."""
    if 'cxx' not in data or 'cxxflags' not in data:
        sys.exit('bench_table: %s: the compiler and flags are not recorded '
                 '(a JSON file of an older make bench?)' % path)
    run = {}
    for r in sah_results(path, data):
        if r.get('version') != 'final':
            continue
        speeds = {}
        for rays in RAYS:
            v = r['rays'].get(rays)
            if v is None or 'ratio' not in v:
                sys.exit('bench_table: %s: %d triangles: no %s with a ratio'
                         % (path, r['triangles'], rays))
            if v.get('reference') == 'MISMATCH':
                sys.exit('bench_table: %s: %d triangles: %s: %d hits, not the '
                         'reference count' % (path, r['triangles'], rays, v['hits']))
            speeds[rays] = (v['mrays_per_s'], v['ratio'])
        run[r['triangles']] = (r['build_ms'], speeds)
    return run


def configuration_table(paths):
    configurations, meshes = {}, None
    for path in paths:
        data = load(path)
        run = configuration_rounds(path, data)
        if meshes is None:
            meshes = sorted(run)
        if sorted(run) != meshes:
            sys.exit('bench_table: %s: meshes of %s triangles, where %s has %s'
                     % (path, sorted(run), paths[0], meshes))
        name = '`%s %s`' % (data['cxx'], data['cxxflags'])
        configurations.setdefault(name, []).append(run)
    median = statistics.median
    rows = []
    for name, runs in configurations.items():
        cells = []
        for triangles in meshes:
            for rays in RAYS:
                speed = median(run[triangles][1][rays][0] for run in runs)
                ratio = median(run[triangles][1][rays][1] for run in runs)
                cells.append('%.3g (%.2f×)' % (speed, ratio))
        for triangles in meshes:
            cells.append('%.0f' % median(run[triangles][0] for run in runs))
        rows.append([name] + cells)
    header = (['compiler and flags'] +
              ['%s, %s' % ('{:,}'.format(t), RAY_NAMES[r])
               for t in meshes for r in RAYS] +
              ['%s, build ms' % '{:,}'.format(t) for t in meshes])
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
