#!/usr/bin/env python3
"""Turn the JSON of `make bench` into a whitespace-separated table for a plot.

    tools/bench_table.py figures/data/bvhbench-levels.json > figures/bvh-bench.dat

One row per mesh (sorted by triangle count) with, for the SAH trees of the
first and the final version: build time in ms and Mrays/s for the camera rays
and for the incoherent rays. The first line names the columns, which the
book's plot (pgfplots, chapter 6) reads by name. Fails, naming the file, if a
value is missing.
"""
import json
import sys

RAYS = ('rays_primary.bin', 'rays_incoherent.bin')
VERSIONS = ('first', 'final')


def main(path):
    try:
        with open(path, encoding='utf-8') as f:
            results = json.load(f)['results']
    except (OSError, ValueError, KeyError) as e:
        sys.exit('bench_table: %s: %s' % (path, e))
    rows = {}
    for r in results:
        if r.get('method') != 'SAH' or r.get('version') not in VERSIONS:
            continue
        row = rows.setdefault(r['triangles'], {})
        row[r['version'], 'build'] = r['build_ms']
        for rays in RAYS:
            if rays in r['rays']:
                row[r['version'], rays] = r['rays'][rays]['mrays_per_s']
    if not rows:
        sys.exit('bench_table: %s: no SAH results' % path)
    columns = [(v, k) for v in VERSIONS for k in ('build',) + RAYS]
    print('triangles ' + ' '.join('%s_%s' % (v, k.split('.')[0])
                                  for v, k in columns))
    for triangles in sorted(rows):
        row = rows[triangles]
        missing = [c for c in columns if c not in row]
        if missing:
            sys.exit('bench_table: %s: %d triangles: no %s' % (path, triangles, missing))
        print(triangles, ' '.join('%.6g' % row[c] for c in columns))


if __name__ == '__main__':
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
