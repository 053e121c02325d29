#!/usr/bin/env python3
"""noweb filter: label each piece of tangled code with its fragment name.

notangle runs this between noweb's markup and its tangler (notangle -filter).
It reads noweb's pipeline representation on stdin and, after the header line
of the first definition of every fragment that is not a root, inserts a C++
comment naming the fragment. The readable tangle in tangled/ then shows where
each piece of code comes from in the book, the way pbrt's own sources do.

A fragment's continuations (its later definitions) get no comment of their
own: nt expands a use of a fragment into all its definitions in order, so the
comment in the first one heads each expansion once, however many
continuations follow it, and a fragment used in two places is named in both.
"""
import sys


def main():
    lines = sys.stdin.read().split('\n')
    # Roots are the chunks that no other chunk uses; they become files and get
    # no comment of their own (tools/noweb/tangle.py writes a file header instead).
    used = {line[len('@use '):] for line in lines if line.startswith('@use ')}
    out = []
    named = set()   # fragments whose first definition has its comment
    pending = None  # fragment name waiting for the end of its header line
    for line in lines:
        out.append(line)
        if line.startswith('@defn '):
            name = line[len('@defn '):]
            pending = name if name in used and name not in named else None
            named.add(name)
        elif line == '@nl' and pending is not None:
            out.append('@text // ' + pending)
            out.append('@nl')
            pending = None
    sys.stdout.write('\n'.join(out))


if __name__ == '__main__':
    main()
