#!/usr/bin/env python3
"""layout_check.py BOOK.layout: fail when a fragment came apart on the page.

tools/book/preamble.tex writes BOOK.layout while pdflatex ships out the pages: one
line "kind what page" per event, in the order of the pages, so in reading
order (a page's top floats before its text):

    header chunk:2.11 10     a fragment's header line
    first chunk:2.11 10      the last of the code lines kept with the header
    last chunk:2.11 11       the first of the code lines kept with the footer
    footer chunk:2.11 11     its "Used in / Defines" lines
    float figure 2.1 67      a figure or table
    cite fig:bvh-splits 211  a reference to a float (in the main matter)

The check fails, naming the page and the fragment, on a header that ends a
page without its first lines of code, on a footer that opens a page without
the last lines, on a float between a fragment's header and its footer, and on
a float printed more than MAX_FLOAT_DISTANCE pages after its first citation
or more than a page before it, and on a float with a label that nothing cites.
The labels of the floats come from BOOK.aux.
"""
import os
import re
import sys

MAX_FLOAT_DISTANCE = 3


def read_events(path):
    events = []
    with open(path, encoding='utf-8', errors='replace') as f:
        for number, line in enumerate(f, 1):
            parts = line.split()
            if not parts:
                continue
            if parts[0] == 'float' and len(parts) == 4:
                events.append(('float', parts[1] + ' ' + parts[2], parts[3]))
            elif len(parts) == 3:
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


def check(events, labels):
    problems = []
    fragments = {}     # label -> {kind: page}
    order = []
    open_fragment = None
    floats = []        # (name, page, fragment it landed in or None)
    first_cite = {}
    for kind, what, page in events:
        if kind == 'header':
            fragments[what] = {'header': page}
            order.append(what)
            open_fragment = what
        elif kind in ('first', 'last', 'footer'):
            fragments.setdefault(what, {})[kind] = page
            if kind == 'footer' and open_fragment == what:
                open_fragment = None
        elif kind == 'float':
            floats.append((what, page, open_fragment))
        elif kind == 'cite':
            first_cite.setdefault(what, page)

    for label in order:
        pages = fragments[label]
        number = label.split(':', 1)[1]
        missing = [k for k in ('header', 'first', 'last', 'footer') if k not in pages]
        if missing:
            problems.append('fragment %s: no %s in the layout record (are its lines counted '
                            'right?)' % (number, ' or '.join(missing)))
            continue
        if pages['header'] != pages['first']:
            problems.append('page %s ends with the header of fragment %s, whose first '
                            'lines of code are on page %s' %
                            (pages['header'], number, pages['first']))
        if pages['footer'] != pages['last']:
            problems.append('page %s opens with the footer of fragment %s, cut from its '
                            'last lines of code on page %s' %
                            (pages['footer'], number, pages['last']))

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
