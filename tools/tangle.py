#!/usr/bin/env python3
"""Tangle the chapters into a directory of source files, one per root chunk.

    tools/tangle.py --out DIR [--line-directives] CHAPTER.md...

Roots are found with noroots; each is extracted with notangle and written
through cpif, so a file whose text did not change keeps its mtime and make
rebuilds only what changed. Files in DIR that are no longer roots are removed,
so DIR is exactly what the chapters tangle to.

--line-directives tangles for the compiler: #line directives point every
diagnostic at chapters/NN-slug.md and its line. Without it, the tangle is the
readable copy kept in tangled/: fragment names as comments, no directives.

Run from the repository root so that the file names in #line directives are
the chapters' paths as a reader sees them.
"""
import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
LINE_FORMAT = '#line %L "%F"%N'
# Exercise markers (// BEGIN SOLUTION ...) and stub blocks never reach the
# tangle: see tools/exercise_filter.py and docs/exercises.md.
EXERCISES_FILTER = ['-filter', 'python3 ' + os.path.join(HERE, 'exercise_filter.py')]


def fail(message):
    sys.exit('tangle: ' + message)


def run(cmd, stdin=None):
    proc = subprocess.run(cmd, input=stdin, capture_output=True, text=True)
    # notangle reports an undefined chunk on stderr and still writes output:
    # anything on stderr is an error here, never a warning to scroll past.
    if proc.returncode != 0 or proc.stderr.strip():
        fail('%s failed:\n%s' % (' '.join(cmd[:2]), proc.stderr.strip()))
    return proc.stdout


def roots_by_chapter(chapters):
    """Map each root chunk to the chapter that defines it (from noweb markup)."""
    roots = [line.strip()[2:-2] for line in run(['noroots'] + chapters).splitlines()
             if line.strip()]
    defined_in = {}
    current = None
    for line in run(['/usr/lib/noweb/markup'] + chapters).splitlines():
        if line.startswith('@file '):
            current = line[len('@file '):]
        elif line.startswith('@defn '):
            defined_in.setdefault(line[len('@defn '):], current)
    for root in roots:
        if root.startswith('/') or '..' in root.split('/') or ' ' in root:
            fail('%s: root chunk <<%s>> is not a relative file path'
                 % (defined_in.get(root), root))
    return {root: defined_in[root] for root in roots}


def header(root, chapter):
    comment = '#' if root.endswith(('.py', '.sh', '.gp')) else '//'
    return ('%s %s: tangled from %s. Edit the chapter, not this file.\n'
            % (comment, root, chapter))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--out', required=True)
    parser.add_argument('--line-directives', action='store_true')
    parser.add_argument('chapters', nargs='+')
    args = parser.parse_args()

    roots = roots_by_chapter(args.chapters)
    for root, chapter in sorted(roots.items()):
        if args.line_directives:
            code = run(['notangle', '-L' + LINE_FORMAT] + EXERCISES_FILTER +
                       ['-R' + root] + args.chapters)
        else:
            code = header(root, chapter) + run(
                ['notangle'] + EXERCISES_FILTER + ['-filter',
                 'python3 ' + os.path.join(HERE, 'fragment_comments.py'),
                 '-R' + root] + args.chapters)
        if not code.endswith('\n'):
            code += '\n'
        path = os.path.join(args.out, root)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        run(['cpif', path], stdin=code)
        os.chmod(path, 0o644)  # cpif creates new files with mode 0600

    wanted = {os.path.normpath(os.path.join(args.out, r)) for r in roots}
    for top, dirs, files in os.walk(args.out, topdown=False):
        for name in files:
            path = os.path.normpath(os.path.join(top, name))
            if path not in wanted:
                os.remove(path)
        if top != args.out and not os.listdir(top):
            os.rmdir(top)


if __name__ == '__main__':
    main()
