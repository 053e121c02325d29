"""The grader's outputs for one submission (Report): results.json
(Gradescope), junit.xml and results.txt, rewritten whole after every
test; a test's result (Result), and what a student may see of its failure
(shown_message)."""
import json
import os
import re
import xml.etree.ElementTree as ET

from tools.grading.files import atomic_write

MAX_SHOWN = 4000              # characters of a failure shown
# Failures that the judge's own code reports (a worker that crashed, hung or
# ran out of memory) name this file; of a hidden test's, their first words
# are shown (shown_message).
JUDGE_SOURCE = 'tests/calls/judge.cpp'


class Result:
    def __init__(self, exercise, chapter, suite, name, hidden, max_score, hint):
        self.exercise, self.chapter = exercise, chapter
        self.suite, self.name, self.hidden = suite, name, hidden
        self.max_score, self.hint = max_score, hint
        self.status, self.message = 'NOT-RUN', 'not run yet'
        self.failures = []   # the judge's failure messages
        self.threw = ''      # the call whose exception failed the test
        # The messages of the exercise's own stubs, which a hidden test's
        # failure may show (shown_message).
        self.stubs = frozenset()

    @property
    def full(self):
        return '%s.%s' % (self.suite, self.name)

    @property
    def score(self):
        return self.max_score if self.status == 'PASS' else 0.0


def first_line(text):
    m = re.search(r'C\+\+ exception with description "(.*?)" thrown', text or '', re.S)
    if m:
        return ('threw: ' + ' '.join(m.group(1).split()))[:160]
    lines = [line.strip() for line in (text or '').splitlines()
             if line.strip() and line.strip() != 'unknown file']
    if len(lines) > 1 and re.match(r'^\S+:\d+$', lines[0]):   # gtest's file:line
        return ('%s: %s' % (lines[0], lines[1]))[:160]
    return lines[0][:160] if lines else ''


def fence_safe(text):
    """Text that cannot close the Markdown code block it is shown in."""
    return text.replace('`' * 3, '` ` `')


def clean(text, limit=MAX_SHOWN):
    """Text that may come from the student's code (what it threw), as it is
    shown: printable, and not too long."""
    text = re.sub(r'[^\x20-\x7e\n\t\u00a0-\uffff]', '?', text or '')
    return text if len(text) <= limit else text[:limit] + ' [...]'


# The judge's words on a call that failed in the worker, as the judge's
# failure reads them: "tests/calls/judge.cpp:LINE", GoogleTest's "Failed",
# then "during Call: KIND: DETAIL" (tests/calls/judge.cpp, Kind). Of a hidden
# test, only "during Call: KIND" is shown: the detail is the code's to choose.
# Matched from the start: the first "during" is the judge's own.
WORKER_FAILURE = re.compile(r'%s:\d+\n(?:Failed\n)?(during [A-Za-z_]\w*: (?:the code crashed|'
                            r'the code took too long|the code ran out of memory|the answer '
                            r'was refused))(?=:|$)' % re.escape(JUDGE_SOURCE), re.M)
THROWN = re.compile(r'C\+\+ exception with description "(.*?)" thrown', re.S)
HIDDEN_CHECK = 'a hidden test failed (its checks are not shown)'


def shown_message(result):
    """What a student may see of a test's failure: everything for a public
    test. A hidden test's worker saw the test's inputs, so what a student
    sees of its failure holds nothing that the student's code chose, which
    could carry them: never the test's checks (the values the code returned)
    nor what the code threw, a signal or an exit status, only the kind of
    failure (the code threw, crashed, took too long, ran out of memory) and
    the call, whose name is public. Only the message of one of the
    exercise's own stubs is shown as thrown: an unfinished exercise says so,
    and the code can choose no more than which stub it throws."""
    if not result.hidden or not result.failures:
        return clean(result.message)
    call = result.threw if re.fullmatch(r'[A-Za-z_]\w*', result.threw or '') else ''
    shown = []
    for failure in result.failures:
        thrown = THROWN.search(failure)
        worker = WORKER_FAILURE.match(failure)
        if thrown and thrown.group(1) in result.stubs:
            text = 'threw: ' + thrown.group(1)
        elif thrown:
            text = '%sthe code threw an exception (not shown for a hidden test)' % (
                'during %s: ' % call if call else '')
        elif worker:
            text = worker.group(1)
        else:
            text = HIDDEN_CHECK
        if text not in shown:
            shown.append(text)
    return clean('\n'.join(shown))


class Report:
    def __init__(self, out, sub_label):
        self.out, self.label = out, sub_label
        self.results = []
        self.notes = []        # Markdown lines for the top-level output
        self.exercises = []    # (chapter, exercise id, points)
        self.failed = False    # the grader itself failed somewhere
        self.secret = None     # of the random cases, to repeat a grading (--seed)
        os.makedirs(out, exist_ok=True)

    def exercise_scores(self):
        rows = []
        for chapter, ident, points in self.exercises:
            rs = [r for r in self.results if r.exercise == ident]
            got = sum(r.score for r in rs)
            statuses = sorted({r.status for r in rs})
            rows.append((chapter, ident, round(got, 4), points, statuses))
        return rows

    def write(self):
        total = sum(r.score for r in self.results)
        maximum = sum(p for _, _, p in self.exercises)
        tests = []
        for number, r in enumerate(self.results, 1):
            message = shown_message(r)
            md = ['**%s**%s' % (r.status, ' (hidden test)' if r.hidden else '')]
            if message:
                md.append('```\n%s\n```' % fence_safe(message))
            if r.status != 'PASS' and r.hint:
                md.append('Hint: ' + r.hint)
            tests.append({'name': '%s %s' % (r.exercise, r.full),
                          'number': '%s.%d' % (r.exercise[len('ex-'):], number),
                          'score': round(r.score, 4), 'max_score': round(r.max_score, 4),
                          'status': 'passed' if r.status == 'PASS' else 'failed',
                          'output': '\n\n'.join(md), 'output_format': 'md',
                          'visibility': 'after_published' if r.hidden else 'visible',
                          'tags': [r.status]})
        data = {'score': round(total, 4), 'max_score': maximum,
                'output': '\n'.join(self.notes) or 'Graded.', 'output_format': 'md',
                'stdout_visibility': 'hidden', 'visibility': 'visible', 'tests': tests,
                'extra_data': {'submission': self.label, 'secret': self.secret,
                               'exercises': [
                    {'chapter': c, 'exercise': i, 'points': g, 'max_points': p,
                     'statuses': s} for c, i, g, p, s in self.exercise_scores()]}}
        atomic_write(os.path.join(self.out, 'results.json'), json.dumps(data, indent=1))
        atomic_write(os.path.join(self.out, 'junit.xml'), self.junit())
        atomic_write(os.path.join(self.out, 'results.txt'), self.table(total, maximum))

    def junit(self):
        suites = ET.Element('testsuites', name='lrt grading: ' + self.label)
        for chapter, ident, got, points, _ in self.exercise_scores():
            rs = [r for r in self.results if r.exercise == ident]
            suite = ET.SubElement(suites, 'testsuite', name=ident, tests=str(len(rs)),
                                  failures=str(sum(r.status == 'FAIL' for r in rs)),
                                  errors=str(sum(r.status not in ('PASS', 'FAIL', 'NOT-RUN')
                                                 for r in rs)),
                                  skipped=str(sum(r.status == 'NOT-RUN' for r in rs)))
            for r in rs:
                case = ET.SubElement(suite, 'testcase', classname='%s.%s' % (ident, r.suite),
                                     name=r.name)
                if r.status == 'FAIL':
                    ET.SubElement(case, 'failure', message=first_line(shown_message(r)),
                                  type='FAIL').text = shown_message(r)
                elif r.status == 'NOT-RUN':
                    ET.SubElement(case, 'skipped', message=first_line(r.message))
                elif r.status != 'PASS':
                    ET.SubElement(case, 'error', message=first_line(shown_message(r)),
                                  type=r.status).text = shown_message(r)
        return ET.tostring(suites, encoding='unicode') + '\n'

    def table(self, total, maximum):
        lines = ['Submission: %s' % self.label, '']
        lines += [re.sub(r'[`*]', '', n) for n in self.notes]
        if self.notes:
            lines.append('')
        for chapter, ident, got, points, statuses in self.exercise_scores():
            lines.append('chapter %s  %-8s %6.2f / %g' % (chapter, ident, got, points))
            for r in (r for r in self.results if r.exercise == ident):
                lines.append('    %-13s %5.2f/%-5.2f %s%s  %s' % (
                    r.status, r.score, r.max_score, r.full, ' (hidden)' if r.hidden else '',
                    first_line(shown_message(r))))
        lines += ['', 'total %.2f / %g' % (total, maximum)]
        return '\n'.join(lines) + '\n'

