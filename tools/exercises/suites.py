"""The tests of the exercises: a test of exercise ex-5.1 is an EXERCISE_TEST in a
suite named Ex5_1_*, public in tests/ch05/, hidden in tests/hidden/ch05/. This
reads the tests of a Book's chapters, gives each exercise its tests, and
reports the names that break the convention (docs/exercises.md).
"""
import os
import re

from tools.exercises.attributes import EXERCISE_ID

TEST_MACRO = re.compile(r'^\s*(TEST|TEST_F|TEST_P|TYPED_TEST|TYPED_TEST_P|EXERCISE_TEST)\s*\('
                        r'\s*(\w+)\s*,\s*(\w+)\s*\)')
EXERCISE_SUITE = re.compile(r'(?:^|/)Ex(\d+)_(\d+)_\w+$')
LOOKS_LIKE_EXERCISE_SUITE = re.compile(r'(?:^|/)Ex\d')


def test_files(root, directory):
    path = os.path.join(root, directory)
    if not os.path.isdir(path):
        return []
    return sorted(os.path.join(directory, name) for name in os.listdir(path)
                  if name.endswith(('.cpp', '.h', '.hpp', '.cc')))


def scan_tests(root, directory):
    """(suite, name, path, line) for every TEST(...) in a directory's files."""
    found = []
    for path in test_files(root, directory):
        with open(os.path.join(root, path), encoding='utf-8',
                  errors='replace') as f:
            for n, text in enumerate(f, 1):
                match = TEST_MACRO.match(text)
                if match:
                    found.append((match.group(2), match.group(3), path, n,
                                  match.group(1)))
    return found


def check_tests(book):
    """Gives each exercise of the book its public and hidden tests, reporting
    test names that break the convention into book.errors."""
    hidden_required = os.path.isdir(os.path.join(book.root, 'tests', 'hidden'))
    for chapter in book.chapters:
        if chapter.number is None:
            continue
        for hidden, directory in ((False, 'tests/ch%s' % chapter.number),
                                  (True, 'tests/hidden/ch%s' % chapter.number)):
            for suite, name, path, line, macro in scan_tests(book.root, directory):
                if hidden:
                    book.hidden.append((suite, name, path, line))
                else:
                    book.public_suites.setdefault(suite, []).append((path, line, name))
                exercise_id = suite_exercise(suite)
                if exercise_id is None:
                    if LOOKS_LIKE_EXERCISE_SUITE.search(suite):
                        book.error(path, line, 'test suite %s looks like an exercise\'s '
                                   'but is not named ExN_K_Name' % suite)
                    elif hidden:
                        book.error(path, line, 'hidden test suite %s names no exercise: '
                                   'hidden tests are named ExN_K_Name' % suite)
                    continue
                exercise = book.by_id.get(exercise_id)
                if exercise is None:
                    book.error(path, line, 'test suite %s names exercise %s, which does '
                               'not exist' % (suite, exercise_id))
                elif exercise.chapter != chapter.number:
                    book.error(path, line, 'test suite %s names exercise %s of chapter '
                               '%s; it belongs in tests/%sch%s/'
                               % (suite, exercise_id, exercise.chapter,
                                  'hidden/' if hidden else '', exercise.chapter))
                else:
                    if macro != 'EXERCISE_TEST':
                        book.error(path, line, 'test %s.%s of exercise %s is declared '
                                   'with %s: declare it with EXERCISE_TEST and reach the '
                                   'exercise\'s code through its exercise calls '
                                   '(tests/calls/calls.h)' % (suite, name, exercise_id,
                                                              macro))
                    (exercise.hidden_tests if hidden else
                     exercise.public_tests).append((suite, name, path, line))
        # The grader compiles a chapter's public and hidden tests into one
        # judge (tests/calls/judge.cpp): a name may not be defined twice.
        public = {}
        for exercise in chapter.exercises:
            for suite, name, path, line in exercise.public_tests:
                public['%s.%s' % (suite, name)] = (path, line)
            for suite, name, path, line in exercise.hidden_tests:
                if '%s.%s' % (suite, name) in public:
                    book.error(path, line, 'hidden test %s.%s has the name of a public '
                               'test (%s:%d): give it another'
                               % ((suite, name) + public['%s.%s' % (suite, name)]))
        for exercise in chapter.exercises:
            if not exercise.id or not EXERCISE_ID.match(exercise.id):
                continue
            if not exercise.public_tests:
                book.error(exercise.path, exercise.line, 'exercise %s has no tests: add '
                           'a suite named %sName in tests/ch%s/'
                           % (exercise.id, exercise.suite_prefix, chapter.number))
            if hidden_required and not exercise.hidden_tests:
                book.error(exercise.path, exercise.line, 'exercise %s has no hidden '
                           'tests: add a suite named %sName in tests/hidden/ch%s/'
                           % (exercise.id, exercise.suite_prefix, chapter.number))


def suite_exercise(suite):
    """The exercise id that a suite name gives (Ex5_1_Name: ex-5.1), or None."""
    match = EXERCISE_SUITE.search(suite)
    return 'ex-%d.%d' % (int(match.group(1)), int(match.group(2))) if match else None
