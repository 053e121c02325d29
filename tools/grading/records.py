"""The judge's records (tests/calls/judge.cpp, ResultLines), read with a
schema: a line of JSON per finished test,

    {"test": "Suite.Name", "verdict": "PASS", "failures": [...]}

verdict one of VERDICTS, each failure one of the kinds of FAILURE_FIELDS:
a check of the test's own ("check"), a worker that failed during a call
("worker": crashed, timed out, ran out of memory, or sent an answer the
judge refused), or an exception that left the test's body ("threw": with
the call whose reply threw it, "" if none did). The grader decides a test's
status and what a student sees of it from these fields alone, never from
a failure's words: those may hold whatever the student's code returned or
threw. The judge alone writes the file, and what the code chose is only
ever the value of a string field (text, detail, message); a record that
does not fit the schema is not believed (its test has no verdict)."""
import json
import re

VERDICTS = ('PASS', 'FAIL', 'CRASH', 'TIMEOUT', 'OOM')
# A worker's failure, as the judge names it, and as a student reads it
# (with the call: "during Intersect: the code crashed").
WORKER_FAILURES = {'crashed': 'the code crashed', 'timeout': 'the code took too long',
                   'oom': 'the code ran out of memory', 'refused': 'the answer was refused'}
# The name of an exercise call: the book's (tests/chNN/exercise_calls.h).
CALL = re.compile(r'[A-Za-z_]\w*')


def is_call(value):
    return isinstance(value, str) and CALL.fullmatch(value) is not None


def is_text(value):
    return isinstance(value, str)


# The fields of each kind of failure, besides "kind", and a test each value
# must pass.
FAILURE_FIELDS = {
    'check': {'where': is_text, 'text': is_text},
    'worker': {'call': is_call, 'failure': lambda v: v in WORKER_FAILURES,
               'detail': is_text},
    'threw': {'call': lambda v: v == '' or is_call(v),
              'message': lambda v: v is None or is_text(v)},
}


def failure(value):
    """A failure of a record as a dict of exactly its kind's fields, or a
    ValueError."""
    if not isinstance(value, dict):
        raise ValueError('a failure is not an object')
    fields = FAILURE_FIELDS.get(value.get('kind'))
    if fields is None or set(value) != set(fields) | {'kind'}:
        raise ValueError('a failure of no known kind, or with other fields')
    for name, valid in fields.items():
        if not valid(value[name]):
            raise ValueError('a failure\'s %s is not what it must be' % name)
    return dict(value)


def failures(value):
    """A list of failures (failure), or a ValueError."""
    if not isinstance(value, list):
        raise ValueError('failures is not a list')
    return [failure(f) for f in value]


def record(value):
    """(test, verdict, failures) of a record, or a ValueError."""
    if not isinstance(value, dict) or set(value) != {'test', 'verdict', 'failures'}:
        raise ValueError('a record has the fields test, verdict and failures')
    if not is_text(value['test']) or value['verdict'] not in VERDICTS:
        raise ValueError('a record\'s test or verdict is not what it must be')
    return value['test'], value['verdict'], failures(value['failures'])


def read_report(path):
    """{test: (verdict, failures)} from the judge's report. A line that
    cannot be read (the judge stopped in the middle of it) or does not fit
    the schema costs its own test only: that test has no verdict, the others
    keep theirs."""
    found = {}
    try:
        with open(path, 'rb') as f:
            lines = f.readlines()
    except OSError:
        return found
    for line in lines:
        try:
            test, verdict, listed = record(json.loads(line.decode('utf-8')))
        except (ValueError, TypeError):
            continue
        found[test] = (verdict, listed)
    return found
