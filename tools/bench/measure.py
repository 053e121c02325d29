#!/usr/bin/env python3
"""Measure everything that chapter 7 and Appendix A quote, into one file.

    tools/bench/measure.py --bench BIN --data DIR --out figures/data/bvh-measurements.json

BIN is the benchmark program of Appendix A built with its peer, Embree
(`make bench-embree-build` builds it),
DIR holds the shared generator's data for subdivision levels 0 to 4
(bunny_L0.ply ... bunny_L4.ply, rays_primary.bin, rays_incoherent.bin).
`make book-measurements` runs it with both. In one run, one after the other:

1. speeds: the benchmark with the SAH trees of the three versions on the
   five meshes, with Embree measured in the same rounds, then with the other
   three split methods on the bunnies subdivided twice and four times (L2,
   L4), each with both ray sets; every version of lrt must find the same hits,
   or the run fails (the program itself checks Embree's hits against lrt's,
   ray by ray, and stops on a disagreement);
2. counts: Valgrind's callgrind, per ray, in the benchmark's tracing loop
   (TracePass), on L2 with the SAH trees: instructions, mispredicted branches
   and misses of a simulated 1 MB last-level cache, for 65,536 camera rays
   (the middle 64 rows of the 1024 x 1024 image) and the first 65,536
   incoherent rays, and the same for Embree's tracing loop (valgrind
   emulates no AVX-512, so Embree runs its AVX2 code under callgrind). These
   do not depend on the load of the machine;
3. compilers: the benchmark built five ways (GCC and Clang, -O2, -O3, and
   GCC -O3 -march=native; `make bench-build BENCH_CXX=... BENCH_CXXFLAGS=...`),
   the first and the final version with the SAH trees on L2 and L4, in
   rounds that rotate the order of the configurations, so that a slow spell
   of the machine falls on all of them alike; each round's figures, so that
   a configuration can be compared with another within a round; and
   callgrind's instructions per ray of the final version in each
   configuration that valgrind can run (not -march=native, whose vector
   instructions it may not know).

The output holds the setup (processor, compiler, flags, passes, builds), the
benchmark's results and the counts. tools/bench/book_numbers.py turns it into
the values that the book prints and tools/bench/table.py into the plot's table.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(os.path.dirname(HERE)))

LEVELS = (0, 1, 2, 3, 4)
OTHER_METHODS = 'hlbvh,middle,equalcounts'
VERSIONS = ('first', 'adopted', 'final', 'embree')
RAY_BYTES = 24               # six float32 per ray
CAMERA_RESOLUTION = 1024     # the shared generator's image, row-major
SAMPLE_ROWS = (480, 544)     # the middle 64 rows
SAMPLE_RAYS = 65536
# The benchmarks that callgrind runs for a version: the adopted version copies
# the first version's tree, so the first version's build runs too (callgrind
# counts only inside TracePass, the tracing).
FILTERS = {'first': '^bunny_L2/SAH/first/', 'adopted': '^bunny_L2/SAH/(first/build|adopted/)',
           'final': '^bunny_L2/SAH/final/', 'embree': '^bunny_L2/SAH/embree/'}
LL_CACHE = '1048576,16,64'
# The compiler configurations (compiler, flags, the name the book gives it);
# the first is the library's own, which parts 1 and 2 measure.
CONFIGURATIONS = (('g++', '-O2', 'gcc-O2'), ('g++', '-O3', 'gcc-O3'),
                  ('g++', '-O3 -march=native', 'gcc-O3-native'),
                  ('clang++', '-O2', 'clang-O2'), ('clang++', '-O3', 'clang-O3'))
ROUNDS = 5
ROOT = os.path.dirname(os.path.dirname(HERE))   # size, associativity, line size of the simulated cache
# callgrind's events, summed as the book reports them.
COUNTS = {'instructions': ('Ir',), 'mispredicted_branches': ('Bcm', 'Bim'),
          'cache_misses': ('ILmr', 'DLmr', 'DLmw')}


def fail(message):
    sys.exit('measure: ' + message)


def run(command, what):
    print('measure: ' + what, flush=True)
    r = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True)
    if r.returncode != 0:
        fail('%s failed (exit %d):\n%s' % (what, r.returncode, r.stdout[-4000:]))
    return r.stdout


def processor():
    try:
        with open('/proc/cpuinfo', encoding='utf-8') as f:
            for line in f:
                if line.startswith('model name'):
                    return line.split(':', 1)[1].strip()
    except OSError:
        pass
    return 'unknown processor'


def speeds(bench, data, tmp, passes, builds):
    """The benchmark's results: SAH on every level, the other methods on L2, L4."""
    rays = ['--rays', os.path.join(data, 'rays_primary.bin'),
            '--rays', os.path.join(data, 'rays_incoherent.bin')]
    runs = [([l for l in LEVELS], 'sah'), ([2, 4], OTHER_METHODS)]
    setup, results, agreement = None, [], []
    for i, (levels, methods) in enumerate(runs):
        out = os.path.join(tmp, 'speeds%d.json' % i)
        meshes = [a for l in levels
                  for a in ('--mesh', os.path.join(data, 'bunny_L%d.ply' % l))]
        run([bench] + meshes + rays + ['--methods', methods, '--passes', str(passes),
                                        '--builds', str(builds), '--json', out],
            'the benchmark, %s on levels %s' % (methods, levels))
        with open(out, encoding='utf-8') as f:
            part = json.load(f)
        setup = setup or {k: part[k] for k in ('compiler', 'cxx', 'cxxflags', 'float',
                                               'passes', 'build_repetitions')}
        results += part['results']
        agreement += part.get('agreement', [])
    check_hits(results)
    return setup, results, agreement


def check_hits(results):
    """Every version and method of lrt must find the same hits on a mesh and
    ray set. Embree's triangle test is not lrt's, and a ray through an edge
    may hit on one side only; the program compares its hits with lrt's ray by
    ray, with an allowance, and stops the run on a disagreement."""
    seen = {}
    for r in results:
        if r['version'] == 'embree':
            continue
        for name, v in r['rays'].items():
            key = (r['mesh'], name)
            if seen.setdefault(key, v['hits']) != v['hits']:
                fail('%s, %s: %s %s found %d hits, another version %d' %
                     (r['mesh'], name, r['method'], r['version'], v['hits'], seen[key]))


def samples(data, tmp):
    """The ray files that callgrind traces: camera rows and incoherent rays."""
    row = CAMERA_RESOLUTION * RAY_BYTES
    with open(os.path.join(data, 'rays_primary.bin'), 'rb') as f:
        f.seek(SAMPLE_ROWS[0] * row)
        camera = f.read((SAMPLE_ROWS[1] - SAMPLE_ROWS[0]) * row)
    with open(os.path.join(data, 'rays_incoherent.bin'), 'rb') as f:
        incoherent = f.read(SAMPLE_RAYS * RAY_BYTES)
    files = {}
    for name, rays in (('camera', camera), ('incoherent', incoherent)):
        if len(rays) != SAMPLE_RAYS * RAY_BYTES:
            fail('%s: too few rays for a sample of %d' % (data, SAMPLE_RAYS))
        files[name] = os.path.join(tmp, name + '_sample.bin')
        with open(files[name], 'wb') as f:
            f.write(rays)
    return files


def callgrind_totals(path):
    events = totals = None
    with open(path, encoding='utf-8') as f:
        for line in f:
            if line.startswith('events:'):
                events = line.split()[1:]
            elif line.startswith('summary:'):
                totals = [int(x) for x in line.split()[1:]]
    if not events or not totals:
        fail('%s: no events or summary line' % path)
    return dict(zip(events, totals))


def callgrind(program, data, rays, version, out, simulate=False):
    """callgrind's totals in the tracing loop (TracePass) of `version` on L2
    with the SAH tree, for the rays of the file `rays`; with `simulate`, of
    the branch predictor and the last-level cache too."""
    # Valgrind 3.19 gives up on the DWARF 5 that Clang 14 writes; it needs
    # only the symbols, so it runs a copy without the debugging information.
    plain = out + '.program'
    run(['objcopy', '--strip-debug', program, plain], 'objcopy --strip-debug ' + program)
    simulation = ['--branch-sim=yes', '--cache-sim=yes', '--LL=' + LL_CACHE] if simulate else []
    run(['valgrind', '--tool=callgrind', '--toggle-collect=*TracePass*'] + simulation +
        ['--callgrind-out-file=' + out, plain, '--mesh', os.path.join(data, 'bunny_L2.ply'),
         '--rays', rays, '--methods', 'sah', '--passes', '1', '--builds', '1',
         '--benchmark_filter=' + FILTERS[version]],
        'callgrind, %s, %s version, %s' % (program, version, os.path.basename(rays)))
    totals = callgrind_totals(out)
    if not totals.get('Ir'):
        fail('callgrind counted no instructions in the %s version\'s tracing of %s '
             'by %s (did the benchmark skip it?)' % (version, rays, program))
    return totals


def counts(bench, data, sample, tmp):
    result = {'mesh': 'bunny_L2', 'method': 'SAH', 'rays': SAMPLE_RAYS,
              'camera_rows': list(SAMPLE_ROWS), 'cache': LL_CACHE}
    for name, rays in sample.items():
        for version in VERSIONS:
            totals = callgrind(bench, data, rays, version,
                               os.path.join(tmp, 'callgrind.%s.%s' % (name, version)),
                               simulate=True)
            result.setdefault(name, {})[version] = {
                what: sum(totals.get(e, 0) for e in events) / SAMPLE_RAYS
                for what, events in COUNTS.items()}
    return result


def make(*args):
    """make in the repository, on its own rather than inside the make that ran
    this script (its jobserver is not ours), its output to ours."""
    env = {k: v for k, v in os.environ.items()
           if k not in ('MAKEFLAGS', 'MFLAGS', 'MAKELEVEL', 'MAKEOVERRIDES')}
    r = subprocess.run(['make', '--no-print-directory', '-C', ROOT] + list(args),
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    if r.returncode != 0:
        fail('make %s failed:\n%s' % (' '.join(args), r.stdout[-4000:]))
    return r.stdout


def compilers(data, sample, tmp):
    programs = []
    for cxx, flags, name in CONFIGURATIONS:
        config = ['BENCH_CXX=' + cxx, 'BENCH_CXXFLAGS=' + flags]
        print('measure: building the benchmark with %s %s' % (cxx, flags), flush=True)
        make('-j2', 'bench-build', *config)
        program = make('-s', 'bench-path', *config).split()[0]
        programs.append((cxx, flags, name, os.path.join(ROOT, program)))
    runs = {name: [] for _, _, name, _ in programs}
    for r in range(ROUNDS):
        k = r % len(programs)
        for cxx, flags, name, program in programs[k:] + programs[:k]:
            out = os.path.join(tmp, '%s-%d.json' % (name, r))
            run([program, '--data', data, '--methods', 'sah', '--passes', '1',
                 '--builds', '1', '--benchmark_filter=first|final', '--json', out],
                'round %d of %d: %s %s' % (r + 1, ROUNDS, cxx, flags))
            with open(out, encoding='utf-8') as f:
                part = json.load(f)
            check_hits(part['results'])
            runs[name].append(part)
    result = []
    for cxx, flags, name, program in programs:
        entry = {'name': name, 'cxx': cxx, 'cxxflags': flags,
                 'compiler': runs[name][0]['compiler'], 'rounds': ROUNDS, 'meshes': {}}
        for mesh in ('bunny_L2', 'bunny_L4'):
            finals = [x for part in runs[name] for x in part['results']
                      if x['mesh'] == mesh and x['version'] == 'final']
            if len(finals) != ROUNDS:
                fail('%s: %d results of the final version on %s, not %d'
                     % (name, len(finals), mesh, ROUNDS))
            # In round order: element r of every configuration is round r's.
            m = {'build_ms': [x['build_ms'] for x in finals]}
            for ray_file in ('rays_primary.bin', 'rays_incoherent.bin'):
                m[ray_file] = {what: [x['rays'][ray_file][what] for x in finals]
                               for what in ('mrays_per_s', 'ratio')}
            entry['meshes'][mesh] = m
        if '-march=native' not in flags:
            entry['instructions'] = {
                rays: callgrind(program, data, sample[rays], 'final',
                                os.path.join(tmp, 'cg.%s.%s' % (name, rays)))['Ir'] / SAMPLE_RAYS
                for rays in ('camera', 'incoherent')}
        result.append(entry)
    return result


def embree_version():
    """The version of the Embree headers that the program was compiled with."""
    try:
        with open('/usr/include/embree3/rtcore_config.h', encoding='utf-8') as f:
            for line in f:
                words = line.split()
                if words[:2] == ['#define', 'RTC_VERSION_STRING']:
                    return words[2].strip('"')
    except OSError:
        pass
    fail('no Embree 3 headers (/usr/include/embree3/rtcore_config.h): '
         'tools/deps.sh embree installs them')


def valgrind_version():
    r = subprocess.run(['valgrind', '--version'], stdout=subprocess.PIPE, text=True)
    return r.stdout.strip()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--bench', required=True)
    parser.add_argument('--data', required=True)
    parser.add_argument('--out', required=True)
    parser.add_argument('--passes', type=int, default=5)
    parser.add_argument('--builds', type=int, default=5)
    args = parser.parse_args()
    for level in LEVELS:
        if not os.path.isfile(os.path.join(args.data, 'bunny_L%d.ply' % level)):
            fail('%s: no bunny_L%d.ply (the shared generator with --levels 0,1,2,3,4 '
                 'writes it)' % (args.data, level))
    with tempfile.TemporaryDirectory() as tmp:
        setup, results, agreement = speeds(args.bench, args.data, tmp, args.passes,
                                           args.builds)
        sample = samples(args.data, tmp)
        measured = counts(args.bench, args.data, sample, tmp)
        configurations = compilers(args.data, sample, tmp)
    setup['processor'] = processor()
    setup['rays'] = {name: os.path.getsize(os.path.join(args.data, name)) // RAY_BYTES
                     for name in ('rays_primary.bin', 'rays_incoherent.bin')}
    setup['valgrind'] = valgrind_version()
    setup['embree'] = embree_version()
    data = {'setup': setup, 'results': results, 'agreement': agreement,
            'counts': measured, 'compilers': configurations}
    text = json.dumps(data, indent=1, sort_keys=True)
    tmp_out = args.out + '.tmp'
    with open(tmp_out, 'w', encoding='utf-8') as f:
        f.write(text + '\n')
    os.replace(tmp_out, args.out)
    print('measure: wrote ' + args.out)


if __name__ == '__main__':
    main()
