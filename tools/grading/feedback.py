"""What a student sees of a test's failure, decided from the judge's records
(records.py), never from a failure's words: all of it for a public test
(shown_message), and for a hidden test only the kind of each failure and
the call it happened in (hidden_text); a line of it for the tables
(shown_line)."""
import re

from tools.grading.records import WORKER_FAILURES

MAX_SHOWN = 4000              # characters of a failure shown
HIDDEN_CHECK = 'a hidden test failed (its checks are not shown)'
HIDDEN_THREW = 'the code threw an exception (not shown for a hidden test)'


def first_line(text):
    """The first line of a text, with the next if the first is GoogleTest's
    file:line; at most 160 characters."""
    lines = [line.strip() for line in (text or '').splitlines()
             if line.strip() and line.strip() != 'unknown file']
    if len(lines) > 1 and re.match(r'^\S+:\d+$', lines[0]):   # gtest's file:line
        return ('%s: %s' % (lines[0], lines[1]))[:160]
    return lines[0][:160] if lines else ''


def clean(text, limit=MAX_SHOWN):
    """Text that may come from the student's code (what it threw), as it is
    shown: printable, and not too long. Surrogates and the noncharacters
    U+FFFE and U+FFFF are no characters of XML: junit.xml would not parse."""
    text = re.sub(r'[^\x20-\x7e\n\t\u00a0-\ud7ff\ue000-\ufffd]', '?', text or '')
    return text if len(text) <= limit else text[:limit] + ' [...]'


def public_text(failure):
    """A failure in full, as a public test shows it."""
    kind = failure['kind']
    if kind == 'check':
        return (failure['where'] + '\n' if failure['where'] else '') + failure['text']
    if kind == 'worker':
        return 'during %s: %s: %s' % (failure['call'], WORKER_FAILURES[failure['failure']],
                                      failure['detail'])
    if failure['message'] is None:
        return 'Unknown C++ exception thrown in the test body.'
    return 'C++ exception with description "%s" thrown in the test body.' % failure['message']


def public_line(failure):
    if failure['kind'] == 'threw' and failure['message'] is not None:
        return ('threw: ' + ' '.join(failure['message'].split()))[:160]
    return first_line(public_text(failure))


def hidden_text(failure, stubs):
    """A failure as a hidden test shows it. A hidden test's worker saw the
    test's inputs, so this holds nothing that the student's code chose,
    which could carry them: never the test's checks (the values the code
    returned) nor what the code threw, a signal or an exit status; only the
    kind of failure (the code threw, crashed, took too long, ran out of
    memory) and the call, whose name is the book's. Only the message of one
    of the exercise's own stubs (stubs) is shown as thrown: an unfinished
    exercise says so, and the code can choose no more than which stub it
    throws."""
    kind = failure['kind']
    if kind == 'threw' and failure['message'] in stubs:
        return 'threw: ' + failure['message']
    if kind == 'threw':
        return ('during %s: ' % failure['call'] if failure['call'] else '') + HIDDEN_THREW
    if kind == 'worker':
        return 'during %s: %s' % (failure['call'], WORKER_FAILURES[failure['failure']])
    return HIDDEN_CHECK


def hidden_texts(result):
    """What a hidden test's failures show (hidden_text), each once."""
    found = []
    for failure in result.failures:
        text = hidden_text(failure, result.stubs)
        if text not in found:
            found.append(text)
    return found


def shown_message(result):
    """What a student may see of a test's failure: all of it for a public
    test, what hidden_text keeps for a hidden one."""
    if not result.hidden or not result.failures:
        return clean(result.message)
    return clean('\n'.join(hidden_texts(result)))


def shown_line(result):
    """One line of what a student may see of a test's failure."""
    if result.failures and not result.hidden:
        return clean(public_line(result.failures[0]))
    return first_line(shown_message(result))
