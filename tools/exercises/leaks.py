"""The leak check of a student kit (tools/exercises/kits.py leaks, and the
last step of kits.py build): it searches every file of the kit, the text of
its PDF and of its web pages, and its tarball, for any line of a chosen
exercise's solution that appears nowhere else in the source, any two
consecutive lines of a solution, and the name of any hidden test.

    problems = leaks.find(out, src, edition='student')
"""
import glob
import html
import json
import os
import re
import subprocess
import sys
import tarfile
import tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
from tools.exercises import markup  # noqa: E402
from tools.exercises.kit_common import fail, source_book, stop_on  # noqa: E402

MIN_SOLUTION_CHARS = 12  # shorter solution lines (without spaces) are too common to search


PDF_TEXT_FIXES = {'\u2019': "'", '\u2018': "'", '\u201c': '"', '\u201d': '"',
                  '\u2212': '-', '\u2217': '*', '\ufb01': 'fi', '\ufb02': 'fl',
                  '\u2013': '-', '\u2014': '-', '\u00a0': ' '}
WORD = r'(?<![A-Za-z0-9_])%s(?![A-Za-z0-9_])'


def compact(text):
    return re.sub(r'\s+', '', text)


def pdf_text(data):
    with tempfile.TemporaryDirectory() as tmp:
        pdf = os.path.join(tmp, 'book.pdf')
        with open(pdf, 'wb') as f:
            f.write(data)
        proc = subprocess.run(['pdftotext', '-enc', 'UTF-8', pdf, '-'],
                              capture_output=True, text=True)
        if proc.returncode != 0:
            fail('pdftotext failed on a PDF of the kit: %s' % proc.stderr.strip())
    text = proc.stdout
    for bad, good in PDF_TEXT_FIXES.items():
        text = text.replace(bad, good)
    return text


def kit_files(out, edition):
    """(name, text) for every file of a kit and every member of its tarball;
    PDFs as their text."""
    kit = os.path.join(out, edition)
    for top, dirs, files in os.walk(kit):
        dirs.sort()
        for name in sorted(files):
            full = os.path.join(top, name)
            with open(full, 'rb') as f:
                data = f.read()
            yield os.path.relpath(full, out), data
    tar_path = os.path.join(out, 'lrt-%s.tar.gz' % edition)
    if os.path.exists(tar_path):
        with tarfile.open(tar_path) as tar:
            for member in tar.getmembers():
                if member.isfile():
                    yield ('%s:%s' % (os.path.relpath(tar_path, out), member.name),
                           tar.extractfile(member).read())


def decoded(name, data):
    if name.endswith('.pdf'):
        return pdf_text(data)
    text = data.decode('utf-8', errors='replace')
    if name.endswith('.html'):
        return html_text(text)
    return text


def html_text(text):
    """A web page's text as it reads: highlighted code is cut up by tags, so
    a solution line is whole only without them (a tag gives way to the line
    breaks inside it, so that line numbers stay those of the file)."""
    text = re.sub(r'<[^>]*>', lambda m: '\n' * m.group(0).count('\n'), text)
    return html.unescape(text)


# Two consecutive solution lines found together elsewhere are a leak even if
# each line alone is common: a later chapter that repeats the code, a test
# whose oracle is the solution, a sibling function written the same way.
MIN_PAIR_CHARS = 32


def leak_targets(src, manifest):
    """What must not be in the student kit: {compact text: (exercise,
    chapter path, line, text)} for the solution lines of the chosen exercises
    that appear nowhere else in the source, and for every pair of consecutive
    solution lines; and the hidden test names."""
    book = source_book(src)
    # The chosen exercises, and with a plan those of later assignments.
    chosen = {e['id'] for e in manifest['exercises']} | set(manifest.get('unreleased', []))
    kit_paths = set(manifest['chapters'])
    allowed = []
    solution = []    # (compact text, exercise, chapter path, line, text)
    pairs = []       # the same, for two consecutive lines
    for chapter in book.chapters:
        if chapter.path not in kit_paths:
            continue
        hidden_lines = set()
        for region in chapter.regions:
            if not (region.exercise and region.exercise.id in chosen):
                continue
            code = [(line, text) for line, text in region.solution
                    if compact(text) and not compact(text).startswith('//')]
            for line, text in region.solution:
                hidden_lines.add(line)
                solution.append((compact(text), region.exercise.id, chapter.path,
                                 line, text.strip()))
            for (line, a), (_, b) in zip(code, code[1:]):
                pairs.append((compact(a) + compact(b), region.exercise.id, chapter.path,
                              line, a.strip() + ' / ' + b.strip()))
        allowed.extend(text for n, text in enumerate(chapter.lines, 1)
                       if n not in hidden_lines)
    for path in sorted(glob.glob(os.path.join(src, 'tests', 'ch[0-9][0-9]', '*'))):
        with open(path, encoding='utf-8', errors='replace') as f:
            allowed.append(f.read())
    for name in ('book.md',):
        if os.path.exists(os.path.join(src, name)):
            with open(os.path.join(src, name), encoding='utf-8') as f:
                allowed.append(f.read())
    allowed_text = '\n'.join(allowed)
    allowed_compact = compact(allowed_text)
    lines = {}
    for key, exercise_id, path, line, text in solution:
        if len(key) < MIN_SOLUTION_CHARS or not re.search(r'[A-Za-z]', key):
            continue
        if key in allowed_compact:
            continue
        lines.setdefault(key, (exercise_id, path, line, text))
    for key, exercise_id, path, line, text in pairs:
        if len(key) >= MIN_PAIR_CHARS:
            lines.setdefault(key, (exercise_id, path, line, text))
    names = {}
    for path in sorted(glob.glob(os.path.join(src, 'tests', 'hidden', 'ch[0-9][0-9]'))):
        for suite, name, file, line in scan_tests(path):
            where = '%s:%d' % (os.path.relpath(file, src), line)
            names['%s.%s' % (suite, name)] = where
            for word in (suite, name):
                if not re.search(WORD % re.escape(word), allowed_text):
                    names.setdefault(word, where)
    return lines, names


def scan_tests(directory):
    found = []
    for path in sorted(glob.glob(os.path.join(directory, '*'))):
        with open(path, encoding='utf-8', errors='replace') as f:
            for n, text in enumerate(f, 1):
                match = markup.TEST_MACRO.match(text)
                if match:
                    found.append((match.group(2), match.group(3), path, n))
    return found


def find(out, src, edition='student'):
    manifest_path = os.path.join(out, edition, 'exercises.json')
    if not os.path.exists(manifest_path):
        fail('no kit in %s (run make exercises)' % os.path.join(out, edition))
    with open(manifest_path, encoding='utf-8') as f:
        manifest = json.load(f)
    lines, names = leak_targets(src, manifest)
    name_patterns = [(re.compile(WORD % re.escape(word)), word, where)
                     for word, where in names.items()]
    problems = []
    for name, data in kit_files(out, edition):
        if re.search(r'(^|[/:])(lrt-\w+/)?tests/hidden(/|$)', name):
            problems.append('leak: %s: a hidden test file' % name)
        text = decoded(name, data)
        text_compact = compact(text)
        file_lines = text.split('\n')
        for key, (exercise_id, path, line, solution_text) in lines.items():
            if key in text_compact:
                at = next((i for i, l in enumerate(file_lines, 1) if key in compact(l)), None)
                problems.append('leak: %s%s: solution of %s (%s:%d): %s' % (
                    name, ':%d' % at if at else ' (text)', exercise_id, path, line,
                    solution_text))
        for pattern, word, where in name_patterns:
            match = pattern.search(text)
            if match:
                at = text.count('\n', 0, match.start()) + 1
                problems.append('leak: %s:%d: hidden test name %s (%s)'
                                % (name, at, word, where))
    return problems


def command(args):
    problems = find(os.path.abspath(args.out), os.path.abspath(args.src), args.edition)
    stop_on(problems, '%%d leak(s) in the %s kit' % args.edition)
    print('exercises: no leaks in the %s kit' % args.edition)
