#!/usr/bin/env python3
"""Tangle the chapters into a directory of source files, one per root chunk.

    tools/noweb/tangle.py --out DIR [--line-directives] CHAPTER.md...

The chapters go through noweb's markup and the filters once; each root is
then extracted from that stream with noweb's nt (what notangle does, without
parsing every chapter again per root) and written only if its text changed
(what noweb's cpif does, without a shell and four processes per file), so a
file whose text did not change keeps its mtime and make rebuilds only what
changed. The roots are the chunks defined and never used, as noroots finds
them. Files in DIR that are no longer roots are removed,
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
NOWEB = '/usr/lib/noweb'
LINE_FORMAT = '#line %L "%F"%N'
# Exercise markers (// BEGIN SOLUTION ...) and stub blocks never reach the
# tangle: see tools/noweb/markup_filter.py and docs/exercises.md.
EXERCISES_FILTER = [sys.executable, os.path.join(HERE, 'markup_filter.py')]
COMMENTS_FILTER = [sys.executable, os.path.join(HERE, 'fragment_comments.py')]


def fail(message):
    sys.exit('tangle: ' + message)


def run(cmd, stdin=None):
    proc = subprocess.run(cmd, input=stdin, capture_output=True, text=True)
    # nt reports an undefined chunk on stderr and still writes output:
    # anything on stderr is an error here, never a warning to scroll past.
    if proc.returncode != 0 or proc.stderr.strip():
        name = os.path.basename(cmd[1] if cmd[0] == sys.executable else cmd[0])
        fail('%s failed:\n%s' % (name, proc.stderr.strip()))
    return proc.stdout


def roots_by_chapter(stream):
    """Map each root chunk to the chapter that defines it, from noweb's
    markup: the chunks defined and never used (noroots' rule)."""
    defined_in, used, quoting = {}, set(), False
    current = None
    for line in stream.splitlines():
        if line == '@quote':
            quoting = True
        elif line == '@endquote':
            quoting = False
        elif quoting:
            continue
        elif line.startswith('@file '):
            current = line[len('@file '):]
        elif line.startswith('@defn '):
            defined_in.setdefault(line[len('@defn '):], current)
        elif line.startswith('@use '):
            used.add(line[len('@use '):])
    roots = {name: chapter for name, chapter in defined_in.items() if name not in used}
    for root, chapter in roots.items():
        if root.startswith('/') or '..' in root.split('/') or ' ' in root:
            fail('%s: root chunk <<%s>> is not a relative file path' % (chapter, root))
    return roots


def write_if_changed(path, text):
    """Writes text to path unless the file already holds exactly that text."""
    data = text.encode('utf-8')
    try:
        with open(path, 'rb') as f:
            if f.read() == data:
                return
    except FileNotFoundError:
        pass
    with open(path, 'wb') as f:
        f.write(data)
    os.chmod(path, 0o644)


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

    # As notangle runs it: markup (-t keeps tabs for nt's -L), the filters, nt.
    markup = run([os.path.join(NOWEB, 'markup')] +
                 (['-t'] if args.line_directives else []) + args.chapters)
    roots = roots_by_chapter(markup)
    filtered = run(EXERCISES_FILTER, stdin=markup)
    if not args.line_directives:
        filtered = run(COMMENTS_FILTER, stdin=filtered)
    for root, chapter in sorted(roots.items()):
        nt = [os.path.join(NOWEB, 'nt'), '-R' + root]
        if args.line_directives:
            code = run(nt + ['-t', '-L' + LINE_FORMAT], stdin=filtered)
        else:
            code = header(root, chapter) + run(nt, stdin=filtered)
        if not code.endswith('\n'):
            code += '\n'
        path = os.path.join(args.out, root)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        write_if_changed(path, code)

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
