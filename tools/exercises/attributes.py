"""The pandoc side of the markup that the exercises use: headers, fenced divs
and their attribute lists (`{#id .class key="value"}`), exercise ids and the
chapter file names their numbers come from. Read here as pandoc reads them,
so that the lint and the kits see the exercises the book shows.
"""
import os
import re

HEADER = re.compile(r'^(#{1,6})\s+(.*?)\s*$')
HEADER_ATTRIBUTES = re.compile(r'\s*\{([^{}]*)\}\s*$')
DIV_FENCE = re.compile(r'^:{3,}(.*)$')
ATTRIBUTE = re.compile(r'''\s*(?:\#(?P<id>[^\s}]+)|\.(?P<cls>[^\s}]+)|(?P<key>[\w-]+)=
                           (?:"(?P<dq>(?:[^"\\]|\\.)*)"|'(?P<sq>[^']*)'|(?P<bare>[^\s"'}]+)))''',
                       re.VERBOSE)
EXERCISE_ID = re.compile(r'^ex-(\d+)\.(\d+)$')
CHAPTER_FILE = re.compile(r'^(\d\d)-[^/]*\.md$')


def chapter_number(path):
    match = CHAPTER_FILE.match(os.path.basename(path))
    return match.group(1) if match else None


def parse_attributes(text):
    """Pandoc attributes `#id .class key=value key="v w"` -> (id, classes, dict),
    or None where the text is not a pandoc attribute list."""
    ident, classes, attrs = None, [], {}
    pos = 0
    text = text.strip()
    while pos < len(text):
        match = ATTRIBUTE.match(text, pos)
        if not match or match.end() == pos:
            return None
        if match.group('id'):
            ident = match.group('id')
        elif match.group('cls'):
            classes.append(match.group('cls'))
        else:
            value = match.group('dq')
            if value is not None:
                value = re.sub(r'\\(.)', r'\1', value)
            else:
                value = match.group('sq') if match.group('sq') is not None \
                    else match.group('bare')
            attrs[match.group('key')] = value
        pos = match.end()
        while pos < len(text) and text[pos].isspace():
            pos += 1
    return ident, classes, attrs
