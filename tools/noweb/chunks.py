#!/usr/bin/env python3
"""The noweb chunk grammar of the chapters, read in one place.

    tools/noweb/chunks.py --lua CHAPTER.md...     the chunks as a Lua table (the weave's)

A chapter is Markdown that is also noweb input (DESIGN.md, section 3): a line
`<<Name>>=` at column 1 starts a code chunk; a line `@` or `@ %def id ...` at
column 1 ends it, as does the next `<<Name>>=` line; inside code a line
`<<Name>>` on its own is a use, and `@<<` is an escaped `<<`. Everything else is
documentation, where the fences around chunks stand.

The lint (tools/noweb/lint.py), the exercise markup (tools/exercises/) and the
weave's filters (tools/book/fragments.lua loads the Lua table) take the chunks
from here, so that the book, its checks and its exercises cannot disagree
about where a chunk begins and ends. noweb's own `markup` stays the reference:
the weave checks this reading against it.
"""
import re
import sys

DEFINITION = re.compile(r'^<<(.+)>>=\s*$')
CHUNK_END = re.compile(r'^@(\s|$)')
DEFS = re.compile(r'^@ %def (.*)$')
# A use on a line of its own, the only kind the book allows.
USE_LINE = re.compile(r'^(\s*)<<(.+?)>>\s*$')
# Any use, as notangle reads it: the name ends at the first `>>`, so
# `<<>> <<X>>` is an empty use and a use of X, not one use of `>> <<X`.
USE = re.compile(r'(?<!@)<<(.*?)>>')
UNESCAPED_OPEN = re.compile(r'(?<!@)<<')
FENCE = re.compile(r'^(```|~~~)')


class Chunk:
    """One code chunk: the `<<name>>=` at `line`, its body (the lines up to
    the end, as texts; body line i is line + 1 + i), and how it ended.

    end: the line of the `@` that closes it, or None;
    ended_by: '@', 'definition' (the next chunk began), 'fence' (only when
    read with fenced=True) or 'eof';
    defs: the identifiers of its `@ %def`.
    """
    def __init__(self, name, path, line):
        self.name, self.path, self.line = name, path, line
        self.body = []
        self.end = None
        self.ended_by = 'eof'
        self.defs = []

    def numbered(self):
        """(line number, text) for each line of the body."""
        return [(self.line + 1 + i, text) for i, text in enumerate(self.body)]

    @property
    def uses(self):
        """(line number, name) for each use on a line of its own."""
        return [(n, use.group(2)) for n, use in
                ((n, USE_LINE.match(text)) for n, text in self.numbered()) if use]

    def as_dict(self, lines):
        """What the weave needs, given the chapter's lines: the chunk's text
        from its header to its end, to match it to pandoc's code block."""
        last = self.line + len(self.body) + (1 if self.end else 0)
        return {'name': self.name, 'file': self.path, 'line': self.line,
                'text': '\n'.join(lines[self.line - 1:last]), 'lines': self.body,
                'ended_by': self.ended_by, 'defs': self.defs,
                'uses': [{'line': n, 'name': name} for n, name in self.uses]}


def read_lines(path):
    """The chapter's lines (without their newlines); OSError or
    UnicodeDecodeError where it cannot be read."""
    with open(path, encoding='utf-8') as f:
        return f.read().split('\n')


def parse(lines, path, fenced=False):
    """The chapter in line order: a Chunk where a chunk starts, and
    (line number, text) for each line of documentation.

    fenced=True reads a chapter as pandoc sees it too: a fence line inside
    a chunk ends the chunk (pandoc's code block ends there; noweb would go on
    reading code), and that line is documentation again."""
    items = []
    chunk = None
    for number, text in enumerate(lines, 1):
        if chunk is not None:
            if CHUNK_END.match(text):
                chunk.end, chunk.ended_by = number, '@'
                defs = DEFS.match(text)
                chunk.defs = defs.group(1).split() if defs else []
                chunk = None
                continue
            if DEFINITION.match(text):
                chunk.ended_by = 'definition'
            elif fenced and FENCE.match(text):
                chunk.ended_by = 'fence'
            else:
                chunk.body.append(text)
                continue
            chunk = None
        definition = DEFINITION.match(text)
        if definition:
            chunk = Chunk(definition.group(1), path, number)
            items.append(chunk)
        else:
            items.append((number, text))
    return items


def chunks_of(items):
    return [item for item in items if isinstance(item, Chunk)]


def index(paths):
    """The chunks of the chapters in book order, as the weave reads them."""
    found = []
    for path in paths:
        lines = read_lines(path)
        found.extend(c.as_dict(lines) for c in chunks_of(parse(lines, path, fenced=True)))
    return {'chunks': found}


def lua(value):
    """value (None, bool, int, str, list, dict) as a Lua literal: pandoc 2.17's
    Lua has no JSON reader, but it can load a table."""
    if value is None:
        return 'nil'
    if isinstance(value, bool):
        return 'true' if value else 'false'
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return '"%s"' % ''.join(LUA_ESCAPES.get(c) or ('\\%03d' % ord(c) if ord(c) < 32
                                                        or ord(c) == 127 else c)
                                for c in value)
    if isinstance(value, list):
        return '{%s}' % ', '.join(lua(v) for v in value)
    return '{%s}' % ', '.join('[%s] = %s' % (lua(k), lua(v)) for k, v in value.items())


LUA_ESCAPES = {'\\': '\\\\', '"': '\\"', '\n': '\\n', '\r': '\\r'}


def main(args):
    if args[:1] != ['--lua'] or len(args) < 2:
        sys.exit('usage: chunks.py --lua CHAPTER.md...')
    try:
        table = index(args[1:])
    except (OSError, UnicodeDecodeError) as e:
        sys.exit('chunks.py: cannot read chapter: %s' % e)
    sys.stdout.write('return %s\n' % lua(table))


if __name__ == '__main__':
    main(sys.argv[1:])
