#!/usr/bin/env python3
"""Check that chapters are valid for both noweb and pandoc, with file:line errors.

    tools/noweb/lint.py [--book] CHAPTER.md...     (in chapter order)

--book also checks the chapter file names that the build relies on.

The rules (the README's "Writing a chapter") come from what goes wrong
silently otherwise: notangle drops a whole file on an unescaped <<, reads `a << 2 >> 1` as a
fragment use, turns a missing @ into code that swallows the following prose,
and only warns about undefined fragments. The chunks are read by
tools/noweb/chunks.py, as the exercise tools and the weave read them.
"""
import os
import re
import sys
from collections import defaultdict

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
from tools.noweb import chunks  # noqa: E402
from tools.noweb.chunks import FENCE, UNESCAPED_OPEN, USE_LINE  # noqa: E402

MAX_CODE_COLUMNS = 80
ROOT_NAME = re.compile(r'^[\w.+-]+(/[\w.+-]+)*\.\w+$')
TAB = ('tab character: notangle expands tabs to 8 columns and pandoc to 4; '
       'use spaces')


class Lint:
    def __init__(self):
        self.errors = []

    def error(self, path, line, message):
        self.errors.append('%s:%d: %s' % (path, line, message))

    def check_tab(self, path, number, text):
        if '\t' in text:
            self.error(path, number, TAB)

    def parse(self, path):
        """Returns the chunks of one chapter, reporting format errors. The
        chapter is read as pandoc also reads it (a fence ends a chunk), since
        the book's format is what both tools must agree on."""
        try:
            lines = chunks.read_lines(path)
        except (OSError, UnicodeDecodeError) as e:
            self.error(path, 0, 'cannot read chapter: %s' % e)
            return []
        found = []
        fence_open = None     # line of an open fence in documentation
        fence_taken = 0       # line of a fence that closes a chunk, not documentation's
        for item in chunks.parse(lines, path, fenced=True):
            if isinstance(item, chunks.Chunk):
                fence_taken = self.check_chunk(path, lines, item, fence_open) or fence_taken
                found.append(item)
                fence_open = None
                continue
            number, text = item
            self.check_tab(path, number, text)
            if FENCE.match(text) and number != fence_taken:
                fence_open = number if fence_open is None else None
                following = lines[number] if number < len(lines) else ''
                if fence_open and text.strip() == '```cpp' and \
                        not chunks.DEFINITION.match(following):
                    self.error(path, number, 'a ```cpp block must hold a chunk '
                               '(<<Name>>= on its next line); show code that is not '
                               'part of the library in a ```c++ block')
            if UNESCAPED_OPEN.search(text):
                self.error(path, number, 'unescaped << outside code: notangle reads it '
                           'as a fragment use; write @<<')
        return found

    def check_chunk(self, path, lines, chunk, fence_open):
        """Checks one chunk in its fence; returns the line of the fence that
        closes it, which is not documentation's."""
        number = chunk.line
        self.check_tab(path, number, lines[number - 1])
        previous = lines[number - 2] if number >= 2 else ''
        if fence_open is None or fence_open != number - 1 or \
                not previous.startswith('```cpp'):
            self.error(path, number, 'chunk <<%s>> must follow a ```cpp fence '
                       'line directly' % chunk.name)
        for line, text in chunk.numbered():
            self.check_tab(path, line, text)
            self.check_code_line(path, line, text)
        after = chunk.line + len(chunk.body) + 1   # the @, the fence or the next chunk
        if chunk.ended_by == '@':
            self.check_tab(path, after, lines[after - 1])
            following = lines[after] if after < len(lines) else ''
            if not FENCE.match(following):
                self.error(path, after + 1, 'the fence must close right after '
                           'the @ that ends <<%s>> (one chunk per fence)' % chunk.name)
            return after + 1
        if chunk.ended_by == 'fence':
            self.error(path, chunk.line, 'chunk <<%s>> has no closing @ before '
                       'the fence at line %d' % (chunk.name, after))
            return after
        if chunk.ended_by == 'definition':
            self.error(path, chunk.line, 'chunk <<%s>> is never closed by @: noweb ends '
                       'it where the next chunk starts, at line %d' % (chunk.name, after))
        else:
            self.error(path, chunk.line, 'chunk <<%s>> is never closed by @' % chunk.name)
        return None

    def check_code_line(self, path, number, text):
        shown = text.replace('@<<', '<<')
        if len(shown) > MAX_CODE_COLUMNS:
            self.error(path, number, 'code line has %d columns; the book fits %d'
                       % (len(shown), MAX_CODE_COLUMNS))
        if not UNESCAPED_OPEN.search(text) or USE_LINE.match(text):
            return
        if '>>' in text[UNESCAPED_OPEN.search(text).start():]:
            self.error(path, number, 'noweb reads << ... >> on one line as a fragment '
                       'use: write @<< in code, and put a fragment use on its own line')

    def check_book(self, chapters):
        """Cross-chapter rules: every use defined no later than it is used, every
        fragment reachable from a root, every root defined in one chapter."""
        by_name = defaultdict(list)
        for order, chunks in enumerate(chapters):
            for chunk in chunks:
                by_name[chunk.name].append((order, chunk))
        used = set()
        for order, chunks in enumerate(chapters):
            for chunk in chunks:
                for line, name in chunk.uses:
                    used.add(name)
                    definitions = by_name.get(name)
                    if not definitions:
                        self.error(chunk.path, line, 'use of undefined fragment <<%s>>'
                                   % name)
                    elif definitions[0][0] > order:
                        self.error(chunk.path, line, 'fragment <<%s>> is first defined in '
                                   'a later chapter (%s:%d), so the code as of this '
                                   'chapter cannot tangle' % (name, definitions[0][1].path,
                                                              definitions[0][1].line))
        for name, definitions in by_name.items():
            first = definitions[0][1]
            if name in used:
                continue
            if not ROOT_NAME.match(name):
                self.error(first.path, first.line, 'fragment <<%s>> is defined but never '
                           'used, and its name is not a file path, so no root reaches it'
                           % name)
                continue
            paths = sorted({chunk.path for _, chunk in definitions})
            if len(paths) > 1:
                self.error(first.path, first.line, 'root <<%s>> is defined in more than '
                           'one chapter: %s' % (name, ', '.join(paths)))


# Exercises are labelled ex-6.5 (graded) and ex:name (tools/book/exercises.lua).
LABEL_DEFINITION = re.compile(r'\{[^}]*#((?:sec|fig|eq|tbl|ex):[A-Za-z0-9_-]+|ex-\d+\.\d+)')
LABEL_REFERENCE = re.compile(r'(?<![@\w])@((?:sec|fig|eq|tbl|ex):[A-Za-z0-9_-]*[A-Za-z0-9]'
                             r'|ex-\d+\.\d+)')


def check_references(lint, paths):
    """A reference to a label of a later chapter: a build or an exercise kit of
    the chapters up to this one has no such label and could not weave. Name
    the later chapter in words instead."""
    defined = {}
    texts = []
    for order, path in enumerate(paths):
        try:
            with open(path, encoding='utf-8') as f:
                text = f.read()
        except OSError:
            text = ''
        texts.append(text)
        for number, line in enumerate(text.splitlines(), 1):
            for m in LABEL_DEFINITION.finditer(line):
                defined.setdefault(m.group(1), (order, path, number))
    for order, path in enumerate(paths):
        for number, line in enumerate(texts[order].splitlines(), 1):
            for m in LABEL_REFERENCE.finditer(line):
                where = defined.get(m.group(1))
                if where and where[0] > order:
                    lint.error(path, number, 'reference to %s, which a later chapter '
                               'defines (%s:%d): the chapters up to this one could not '
                               'be woven without it; name that chapter in words'
                               % (m.group(1), where[1], where[2]))


CHAPTER_NAME = re.compile(r'^(\d\d)-[a-z0-9-]+\.md$')


def check_names(lint, paths):
    """The build orders chapters, and cuts the code as of chapter N, by the
    two-digit number that starts each file name: a chapter without one would
    silently drop out of the build."""
    seen = {}
    for path in paths:
        match = CHAPTER_NAME.match(os.path.basename(path))
        if not match:
            lint.error(path, 0, 'a chapter file is named NN-slug.md (two digits, then '
                       'lower-case words joined by -)')
        elif match.group(1) in seen:
            lint.error(path, 0, 'chapter number %s is also used by %s'
                       % (match.group(1), seen[match.group(1)]))
        else:
            seen[match.group(1)] = path


def main(args):
    book = args[:1] == ['--book']
    paths = args[1:] if book else args
    if not paths:
        sys.exit('usage: lint.py [--book] CHAPTER.md...')
    lint = Lint()
    if book:
        check_names(lint, paths)
    chapters = [lint.parse(path) for path in paths]
    lint.check_book(chapters)
    check_references(lint, paths)
    for message in lint.errors:
        print(message, file=sys.stderr)
    if lint.errors:
        print('lint: %d error(s)' % len(lint.errors), file=sys.stderr)
        sys.exit(1)


if __name__ == '__main__':
    main(sys.argv[1:])
