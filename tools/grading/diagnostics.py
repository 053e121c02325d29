"""What a student sees of a build that failed: the first errors of the
compiler's output, at the student's file and line (compiler_errors), or its
last lines (shown_output); a diagnostic at a line whose words must not be
shown (the book's solution of another exercise) as a fixed text."""
import re

FIRST_ERRORS = 10


def region_lines(regions):
    """The chapter's line numbers of the regions, markers and stubs included."""
    return {n for r in regions
            for n in range(r.line(r.begin), r.line(r.stub_end if r.stub_end is not None
                                                   else r.end) + 1)}


# A diagnostic at a line of the book's solution of another exercise (the
# student's code can cause one there: a name it declares that the book's code
# then uses) is shown as this, without its words, which may quote that code.
HIDDEN_DIAGNOSTIC = ('error in the book\'s code of another exercise, which is not shown '
                     '(caused by your code: check the names you declare)')
LOCATION = re.compile(r'^(.*?):(\d+):(?:(\d+):)? ')


def compiler_errors(output, rename):
    """The first error lines of a build, with paths rewritten by rename
    (None: a line whose diagnostics are not shown); each error once (a
    header's error repeats in every file that includes it)."""
    found = []
    lines = output.splitlines()
    for i, line in enumerate(lines):
        m = re.match(r'^(.*?):(\d+):(?:(\d+):)? (fatal error|error): (.*)$', line)
        if m:
            where = rename(m.group(1), int(m.group(2)), m.group(3))
            text = (where + ': error: ' + m.group(5) if where is not None
                    else HIDDEN_DIAGNOSTIC)
        elif 'undefined reference to' in line:
            text = 'link error: ' + line.split(': ', 1)[-1]
        elif line.startswith('tangle: '):
            # the tangle's own message, and notangle's lines after it
            text = '\n'.join([line] + [x for x in lines[i + 1:i + 6]
                                       if x.strip() and not x.startswith(('make', '\t'))])
        else:
            continue
        if text not in found:
            found.append(text)
        if len(found) >= FIRST_ERRORS:
            break
    return found


def shown_output(lines, rename):
    """A build's last lines, where no error line was found, as the student
    may see them: a line at a location whose diagnostics are not shown
    becomes HIDDEN_DIAGNOSTIC. The compiler prints no source lines
    (-fdiagnostics-plain-output), so only a diagnostic's own words are left."""
    shown = []
    for line in lines:
        m = LOCATION.match(line)
        if m and rename(m.group(1), int(m.group(2)), m.group(3)) is None:
            line = HIDDEN_DIAGNOSTIC
        if line not in shown:
            shown.append(line)
    return shown

