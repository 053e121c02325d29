#!/usr/bin/env python3
"""layout_check.py BOOK.layout: fail when a fragment came apart on the page.

tools/book/preamble.tex writes BOOK.layout while pdflatex ships out the pages: one
line per event, in the order of the pages, so in reading order (a page's top
floats before its text):

    header chunk:2.11 7 10   a fragment's header line, its 7 lines of code, page 10
    line chunk:2.11 1 10     line 1 of its code is on page 10 (one such record
                             for each line up to the MIN_LINES-th that is not
                             blank, and from the MIN_LINES-th from the end)
    blank chunk:2.11 2 10    line 2 is on page 10 and is blank
    footer chunk:2.11 11     its "Used in / Defines" lines
    float figure 2.1 67      a figure or table
    cite fig:bvh-splits 211  a reference to a float (in the main matter)

The check fails, naming the page and the fragment, on a header that ends a
page without its first MIN_LINES lines of code (or all of them, in a shorter
fragment), on a footer that opens a page without the last MIN_LINES lines
(blank lines of code do not count), on
a float between a fragment's header and its footer, and on a float printed
more than MAX_FLOAT_DISTANCE pages after its first citation or more than a
page before it, and on a float with a label that nothing cites. The labels of
the floats come from BOOK.aux.
"""
import os
import re
import sys

MAX_FLOAT_DISTANCE = 3
# A fragment cut by a page break keeps at least this many lines of code
# with its header and with its footer.
MIN_LINES = 3
# Records with a number: a header's number of lines, a line's number.
NUMBERED = ('header', 'line', 'blank')


def read_events(path):
    events = []
    with open(path, encoding='utf-8', errors='replace') as f:
        for number, line in enumerate(f, 1):
            parts = line.split()
            if not parts:
                continue
            if parts[0] == 'float' and len(parts) == 4:
                events.append(('float', parts[1] + ' ' + parts[2], parts[3]))
            elif parts[0] in NUMBERED and len(parts) == 4 and parts[2].isdigit():
                events.append((parts[0], (parts[1], int(parts[2])), parts[3]))
            elif parts[0] not in NUMBERED and len(parts) == 3:
                events.append(tuple(parts))
            else:
                raise SystemExit('%s:%d: cannot read this layout line: %r' %
                                 (path, number, line.rstrip('\n')))
    return events


def float_labels(aux):
    """'figure 6.1' -> 'fig:bvh-splits', from \\newlabel lines."""
    labels = {}
    if not os.path.exists(aux):
        return labels
    kinds = {'fig': 'figure', 'tbl': 'table'}
    with open(aux, encoding='utf-8', errors='replace') as f:
        for line in f:
            m = re.match(r'\\newlabel\{((fig|tbl):[^}]*)\}\{\{([^}]*)\}', line)
            if m:
                labels[kinds[m.group(2)] + ' ' + m.group(3)] = m.group(1)
    return labels


def page_number(page):
    return int(page) if page.isdigit() else None


def lines(count):
    return '%d line%s' % (count, '' if count == 1 else 's')


def end_lines(numbers, at, blank):
    """The lines of numbers, in order, up to the MIN_LINES-th that is not
    blank, and the first of them that has no record (or None)."""
    taken, seen = [], 0
    for n in numbers:
        if n not in at:
            return taken, n
        taken.append(n)
        if n not in blank:
            seen += 1
            if seen == MIN_LINES:
                break
    return taken, None


def check(events, labels):
    problems = []
    fragments = {}     # label -> {'lines': n, 'header': page, 'footer': page, 'at', 'blank'}
    order = []
    open_fragment = None
    floats = []        # (name, page, fragment it landed in or None)
    first_cite = {}
    for kind, what, page in events:
        if kind == 'header':
            label, count = what
            fragments[label] = {'header': page, 'lines': count, 'at': {}, 'blank': set()}
            order.append(label)
            open_fragment = label
        elif kind in ('line', 'blank'):
            label, number = what
            record = fragments.setdefault(label, {'at': {}, 'blank': set()})
            record['at'][number] = page
            if kind == 'blank':
                record['blank'].add(number)
        elif kind == 'footer':
            fragments.setdefault(what, {'at': {}, 'blank': set()})['footer'] = page
            if open_fragment == what:
                open_fragment = None
        elif kind == 'float':
            floats.append((what, page, open_fragment))
        elif kind == 'cite':
            first_cite.setdefault(what, page)

    for label in order:
        record = fragments[label]
        number = label.split(':', 1)[1]
        count, at, blank = record['lines'], record['at'], record['blank']
        head, head_missing = end_lines(range(1, count + 1), at, blank)
        tail, tail_missing = end_lines(range(count, 0, -1), at, blank)
        missing = head_missing or tail_missing
        if 'footer' not in record or missing:
            problems.append('fragment %s: no record of its %s in the layout (are its '
                            'lines counted right?)' %
                            (number, 'footer' if 'footer' not in record
                             else 'line %d' % missing))
            continue
        header, footer = record['header'], record['footer']
        # Pages only grow from line to line: the lines with the header are
        # the first of head, those with the footer the first of tail.
        code_lines = [n for n in head if n not in blank]
        with_header = [n for n in code_lines if at[n] == header]
        if at[1] != header:
            problems.append('page %s ends with the header of fragment %s, whose first '
                            'lines of code are on page %s' % (header, number, at[1]))
        elif len(with_header) < len(code_lines):
            away = code_lines[len(with_header)]
            problems.append('page %s ends with the header of fragment %s and only %s of '
                            'its code; line %d is on page %s' %
                            (header, number, lines(len(with_header)), away, at[away]))
        code_lines = [n for n in tail if n not in blank]
        with_footer = [n for n in code_lines if at[n] == footer]
        if at[count] != footer:
            problems.append('page %s opens with the footer of fragment %s, cut from its '
                            'last lines of code on page %s' % (footer, number, at[count]))
        elif len(with_footer) < len(code_lines):
            away = code_lines[len(with_footer)]
            problems.append('page %s opens with only %s of fragment %s before its footer; '
                            'line %d is on page %s' %
                            (footer, lines(len(with_footer)), number, away, at[away]))

    for name, page, inside in floats:
        if inside:
            pages = fragments[inside]
            problems.append('page %s: %s lands inside fragment %s (pages %s-%s)' %
                            (page, name, inside.split(':', 1)[1], pages['header'],
                             pages.get('footer', '?')))
        label = labels.get(name)
        cited = first_cite.get(label) if label else None
        if label and not cited:
            problems.append('page %s: %s (%s) is never cited' % (page, name, label))
        elif cited and page_number(page) is not None and page_number(cited) is not None:
            distance = page_number(page) - page_number(cited)
            if distance > MAX_FLOAT_DISTANCE:
                problems.append('page %s: %s (%s) is printed %d pages after its first '
                                'citation on page %s' % (page, name, label, distance, cited))
            elif distance < -1:
                problems.append('page %s: %s (%s) is printed %d pages before its first '
                                'citation on page %s' % (page, name, label, -distance, cited))
    return problems


def main(argv):
    if len(argv) != 2:
        raise SystemExit('usage: layout_check.py BOOK.layout')
    path = argv[1]
    events = read_events(path)
    if not any(kind == 'header' for kind, _, _ in events):
        raise SystemExit('%s: no fragment in the layout record' % path)
    problems = check(events, float_labels(os.path.splitext(path)[0] + '.aux'))
    for problem in problems:
        print('layout: ' + problem, file=sys.stderr)
    if problems:
        print('layout: %d problem(s) in %s' % (len(problems), path), file=sys.stderr)
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
