"""What a student's code may hold, so that compiling it reads no file and
quotes none of the book's solutions (docs/grading.md, "What a compile sees").

A worker is compiled from the book's code with the student's text in one
exercise's solution regions. That code sits beside the book's solutions of
the other exercises (often in the same function) and the compiler can read
every file of the build, so the student's text must not be able to:

- name a file: `#include "..."` and every other preprocessing directive,
  `asm(".incbin ...")`, and attributes, whose strings some compilers pass to
  the assembler as they are (`section("...")`);
- capture the text around it: a string literal or a comment opened in the
  student's lines that ends in the book's (a raw string `R"(` would hold the
  next exercise's solution), a macro that stringizes the book's code, a
  noweb use `<<Other fragment>>` inside a string, which the tangle replaces
  by that fragment's text there (noweb knows no C++; a use outside literals
  only compiles the book's code in one more place);
- change how the rest is read: a line splice (`\\` at a line's end), a
  trigraph, a digraph, `_Pragma`;
- reach any of these through a macro: names reserved to the implementation
  (`__REDIRECT`, `__STRING`, ...) are refused too;
- enclose the book's text in a bracket it opens: an unbalanced
  `assert((` or `static_assert(false, __STRING((` in one region and `))` in
  the next stringizes the book's solution between them.

check() compares the chapter as it will be compiled with the book's chapter,
chunk by chunk: every chunk must hold exactly the book's sequence of these
constructs (the book's own `#include` lines stay allowed; a student may add
none, change none and remove none), must end outside any comment or literal,
and no comment or literal may run over a region's marker line or hold a
noweb use.
The student's solution regions therefore hold plain C++ statements and
declarations only, which is all an exercise asks for.
"""
import re

from tools.exercises.markup import MARKER, USE  # noqa: E402

# Identifiers that reach the assembler or the preprocessor from C++ text.
BANNED_WORDS = {'asm', '__asm', '__asm__', '_Pragma', '__attribute', '__attribute__',
                '__declspec'}
# A line that only uses a fragment. (USE, a noweb use as notangle finds it,
# anywhere on a line, C++ or not, and MARKER are the exercises' own.)
USE_LINE = re.compile(r'^\s*<<[^<>]+>>\s*$')
TRIGRAPH = re.compile(r"\?\?[=/'()!<>-]")
SPLICE = re.compile(r'\\[ \t]*$')
IDENTIFIER = re.compile(r'[A-Za-z_$\u0080-\U0010ffff][A-Za-z0-9_$\u0080-\U0010ffff]*')
PP_NUMBER = re.compile(r"\.?[0-9](?:[eEpP][+-]|'[0-9A-Za-z_]|[0-9A-Za-z_.])*")
STRING_PREFIXES = ('u8', 'u', 'U', 'L', '')
# Names reserved to the compiler and its library (a leading `__`, or `_` and
# a capital): their macros reach what the words above do, for example
# glibc's __REDIRECT (an asm label of the caller's text), __STRING (`#x`) and
# __glibc_macro_warning1 (a _Pragma).
RESERVED = re.compile(r'__|_[A-Z]')
DIGRAPH = re.compile(r'<:|:>|<%|%>|%:')
OPENERS = '([{'
CLOSERS = {')': '(', ']': '[', '}': '{'}


class Scan:
    """The constructs of one chunk's lines that check() compares.

    items: (line index, kind, text) in order;
    spans: (first, last) line indexes of comments and literals that end on a
           later line than they start;
    open:  None, or (line index, what) of a comment or literal never closed;
    unbalanced: None, or (line index, bracket) of the first bracket that
           closes none, closes another kind, or is never closed."""
    def __init__(self):
        self.items, self.spans, self.open, self.unbalanced = [], [], None, None


def scan(lines):
    """Lexes lines of C++ (phases 1 to 3, as far as the constructs above need)."""
    result = Scan()
    for n, line in enumerate(lines):
        for m in TRIGRAPH.finditer(line):
            result.items.append((n, 'trigraph', m.group(0)))
        if SPLICE.search(line):
            result.items.append((n, 'line splice', line.strip()))
    text = '\n'.join(lines)
    starts = [0]
    for line in lines:
        starts.append(starts[-1] + len(line) + 1)

    def line_at(pos):
        lo, hi = 0, len(lines) - 1
        while lo < hi:
            mid = (lo + hi + 1) // 2
            if starts[mid] <= pos:
                lo = mid
            else:
                hi = mid - 1
        return lo

    def token(kind, begin, end):
        first, last = line_at(begin), line_at(max(end - 1, begin))
        if last > first:
            result.spans.append((first, last))
        if USE.search(text[begin:end]):
            result.items.append((first, 'fragment use inside a %s' % kind,
                                 text[begin:end].split('\n')[0].strip()))

    i, size = 0, len(text)
    stack = []                  # the brackets open so far
    line_start = True           # only blanks and comments so far on this line
    previous = None             # the previous token's text
    while i < size:
        c = text[i]
        if c == '\n':
            line_start = True
            i += 1
            continue
        if c in ' \t\r\f\v':
            i += 1
            continue
        use = USE.match(text, i)
        if use and (i == 0 or text[i - 1] != '@'):
            # A fragment's name is prose: its quotes open no literal.
            i, line_start, previous = use.end(), False, 'use'
            continue
        if text.startswith('//', i):
            end = text.find('\n', i)
            i = size if end < 0 else end
            continue
        if text.startswith('/*', i):
            end = text.find('*/', i + 2)
            if end < 0:
                result.open = (line_at(i), 'a comment')
                token('comment', i, size)
                break
            token('comment', i, end + 2)
            i = end + 2
            continue
        word = IDENTIFIER.match(text, i)
        if word:
            name = word.group(0)
            after = word.end()
            if after < size and text[after] in '"\'' and (
                    name in STRING_PREFIXES or name.endswith('R') and
                    name[:-1] in STRING_PREFIXES and text[after] == '"'):
                i = literal(text, i, after, name.endswith('R'), result, token, line_at)
                if i is None:
                    break
                line_start, previous = False, 'literal'
                continue
            if name in BANNED_WORDS:
                result.items.append((line_at(i), 'keyword', name))
            elif RESERVED.match(name):
                result.items.append((line_at(i), 'reserved name', name))
            i, line_start, previous = after, False, name
            continue
        number = PP_NUMBER.match(text, i)
        if number:
            i, line_start, previous = number.end(), False, number.group(0)
            continue
        if c in '"\'':
            i = literal(text, i, i, False, result, token, line_at)
            if i is None:
                break
            line_start, previous = False, 'literal'
            continue
        if c == '#' or text.startswith('%:', i):
            n = line_at(i)
            if line_start:
                result.items.append((n, 'directive', ' '.join(lines[n].split())))
            else:
                result.items.append((n, 'stringizing outside a directive', c))
            i += 1 if c == '#' else 2
            line_start, previous = False, '#'
            continue
        digraph = DIGRAPH.match(text, i)
        if digraph and not (text.startswith('<::', i) and text[i + 3:i + 4] not in (':', '>')):
            result.items.append((line_at(i), 'digraph', digraph.group(0)))
        if c == '[' and previous == '[':
            result.items.append((line_at(i), 'attribute', '[['))
        if c in OPENERS:
            stack.append(c)
        elif c in CLOSERS:
            if not stack or stack.pop() != CLOSERS[c]:
                result.unbalanced = result.unbalanced or (line_at(i), c)
        i, line_start, previous = i + 1, False, c
    if stack:
        result.unbalanced = result.unbalanced or (len(lines) - 1, stack[-1])
    return result


def literal(text, begin, quote, raw, result, token, line_at):
    """Skips the literal whose quote is at `quote` (its prefix at begin);
    returns where it ends, or None if it never does (result.open says so)."""
    size = len(text)
    if raw:
        paren = text.find('(', quote + 1)
        delimiter = text[quote + 1:paren] if paren >= 0 else None
        if delimiter is None or len(delimiter) > 16 or re.search(r'[\s()\\]', delimiter):
            result.open = (line_at(begin), 'a raw string with no valid delimiter')
            token('raw string', begin, size)
            return None
        end = text.find(')' + delimiter + '"', paren + 1)
        if end < 0:
            result.open = (line_at(begin), 'a raw string')
            token('raw string', begin, size)
            return None
        end += len(delimiter) + 2
        token('raw string', begin, end)
        return end
    close = text[quote]
    i = quote + 1
    while i < size:
        c = text[i]
        if c == '\\':
            i += 2
            continue
        if c == close:
            token('literal', begin, i + 1)
            return i + 1
        if c == '\n':
            break
        i += 1
    result.open = (line_at(begin), 'a string or character literal')
    token('literal', begin, min(i, size))
    return None


# What a solution region may hold, as the grader says it to a student whose
# region is refused.
RULES = ('a solution region holds C++ statements and declarations only, its brackets '
         'balanced; no preprocessing directive, `asm`, attribute, `_Pragma`, name reserved '
         'to the compiler (`__x`, `_X`), line splice, trigraph or digraph, and no comment or '
         'literal left open or holding a fragment use')


def secret_chunks(reference, mine):
    """Names of the chunks of `reference` whose text holds a solution region
    of an exercise other than the one of fragments `mine`, themselves or
    through the fragments they use."""
    secret = {c.name for c in reference.chunks if c.regions and c.name not in mine}
    uses = {}
    for chunk in reference.chunks:
        uses.setdefault(chunk.name, set()).update(
            m.group(1) for line in chunk.body for m in USE.finditer(line))
    grown = True
    while grown:
        grown = False
        for name, used in uses.items():
            if name not in secret and used & secret:
                secret.add(name)
                grown = True
    return secret


def masked(chunk, mine):
    """A chunk's lines as they are compiled, the insides of the regions of
    `mine` left out: stub blocks are never compiled (tools/noweb/markup_filter.py)
    and the grader fills the regions of other exercises without them."""
    lines, skip, stub = [], False, False
    for line in chunk.body:
        marker = MARKER.match(line)
        if marker and marker.group(3) == 'STUB':
            stub = marker.group(2) == 'BEGIN'
        elif stub:
            continue
        elif marker and chunk.name in mine:
            skip = marker.group(2) == 'BEGIN'
            lines.append(line.strip())
        elif not skip and USE_LINE.match(line):
            # A line that only uses a fragment may use another: that
            # compiles other code there (consistent renames), and nothing
            # on the line can take the fragment's text.
            lines.append('<<>>')
        elif not skip:
            lines.append(line.rstrip())
    while lines and not lines[-1]:
        lines.pop()
    return lines


def check(reference, composed, rename, mine):
    """Problems (messages) that keep `composed` (a parsed chapter: the book's
    with a student's text in it for the exercise whose fragments are `mine`)
    from being compiled, compared with the book's chapter `reference`;
    rename(line) names a line of composed as the student knows it (their file
    and line)."""
    problems = []
    book = {}
    for chunk in reference.chunks:
        book.setdefault(chunk.name, []).append(chunk)
    secret = secret_chunks(reference, mine)
    seen = {}
    for chunk in composed.chunks:
        k = seen.get(chunk.name, 0)
        seen[chunk.name] = k + 1
        ours = book.get(chunk.name, [])
        original = ours[k] if k < len(ours) else None
        expected = scan(original.body) if original else Scan()
        found = scan(chunk.body)

        def where(index, chunk=chunk):
            return rename(chunk.line + 1 + index)

        wanted = [(kind, text) for _, kind, text in expected.items]
        for j, (index, kind, text) in enumerate(found.items):
            if j >= len(wanted) or wanted[j] != (kind, text):
                problems.append('%s: %s `%s` in <<%s>>, where the book has none'
                                % (where(index), kind, text, chunk.name))
                break
        else:
            if len(wanted) > len(found.items):
                problems.append('%s: <<%s>> lacks the book\'s %s `%s`'
                                % (where(0), chunk.name, *wanted[len(found.items)]))
        if found.open is not None:
            problems.append('%s: %s in <<%s>> is never closed'
                            % (where(found.open[0]), found.open[1], chunk.name))
        markers = [i for i, line in enumerate(chunk.body) if MARKER.match(line)]
        for first, last in found.spans:
            inside = [i for i in markers if first < i <= last]
            if inside:
                problems.append('%s: a comment or literal in <<%s>> runs over the '
                                'region marker at %s' % (where(first), chunk.name,
                                                         where(inside[0])))
                break
        # Brackets: the book's chunks and regions each balance theirs, so
        # that no code around a region or a fragment use can take it into a
        # macro's argument.
        unbalanced_regions = [(r, inner) for r in chunk.regions
                              for inner in [scan(chunk.body[r.begin + 1:r.end]).unbalanced]
                              if inner is not None]
        for region, inner in unbalanced_regions:
            problems.append('%s: the brackets of the solution region in <<%s>> do not '
                            'balance (`%s`): a region opens and closes its own'
                            % (where(region.begin + 1 + inner[0]), chunk.name, inner[1]))
        if found.unbalanced is not None and not unbalanced_regions:
            problems.append('%s: the brackets of <<%s>> do not balance (`%s`)'
                            % (where(found.unbalanced[0]), chunk.name, found.unbalanced[1]))
        # Where a student may change code outside the regions, no change may
        # touch the text around another exercise's solution.
        if original is not None and chunk.name in secret:
            if masked(chunk, mine) != masked(original, mine):
                problems.append('%s: <<%s>> holds the book\'s solution of another exercise '
                                '(itself or through the fragments it uses): it may change in '
                                'your exercise\'s regions only' % (where(0), chunk.name))
        elif chunk.name not in secret:
            # A chunk that in the book holds no other exercise's solution
            # (or is not in the book) may not come to use one: it could
            # take it into brackets of its own (an assert's argument).
            used = [m.group(1) for line in chunk.body for m in USE.finditer(line)
                    if m.group(1) in secret]
            if used:
                problems.append('%s: <<%s>> uses <<%s>>, which holds the book\'s solution of '
                                'another exercise; the book\'s <<%s>> does not'
                                % (where(0), chunk.name, used[0], chunk.name))
    return problems
