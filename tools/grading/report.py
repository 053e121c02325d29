"""The grader's outputs for one submission (Report): results.json
(Gradescope), junit.xml and results.txt, rewritten whole after every
exercise; and a test's result (Result). What they show of a failure is
feedback.py's to say."""
import json
import os
import re
import xml.etree.ElementTree as ET

from tools.grading.feedback import first_line, public_text, shown_line, shown_message
from tools.grading.files import atomic_write


class Result:
    def __init__(self, exercise, chapter, suite, name, hidden, max_score, hint):
        self.exercise, self.chapter = exercise, chapter
        self.suite, self.name, self.hidden = suite, name, hidden
        self.max_score, self.hint = max_score, hint
        self.status, self.message = 'NOT-RUN', 'not run yet'
        self.failures = []   # the judge's records of its failures (records.py)
        # The messages of the exercise's own stubs, which a hidden test's
        # failure may show (shown_message).
        self.stubs = frozenset()

    @property
    def full(self):
        return '%s.%s' % (self.suite, self.name)

    @property
    def score(self):
        return self.max_score if self.status == 'PASS' else 0.0

    def judged(self, verdict, failures):
        """The judge's verdict on the test, and its failures (records.py)."""
        self.failures = failures
        self.status = 'FAIL' if verdict == 'PASS' and failures else verdict
        self.message = '\n'.join(public_text(f) for f in failures)


def fence_safe(text):
    """Text that cannot close the Markdown code block it is shown in."""
    return text.replace('`' * 3, '` ` `')


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
                    ET.SubElement(case, 'failure', message=shown_line(r),
                                  type='FAIL').text = shown_message(r)
                elif r.status == 'NOT-RUN':
                    ET.SubElement(case, 'skipped', message=first_line(r.message))
                elif r.status != 'PASS':
                    ET.SubElement(case, 'error', message=shown_line(r),
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
                    shown_line(r)))
        lines += ['', 'total %.2f / %g' % (total, maximum)]
        return '\n'.join(lines) + '\n'

