"""Tests of the batch grader's names and identities (tools/grading/grade.py,
docs/grading.md "Batch mode", docs/course.md "The gradebook").

Two holes of the grading wall (issue 39):

- A submission's name becomes a path: OUT/NAME, which the batch empties
  before grading. `...tar.gz` was the name `..` (OUT's parent: other
  students' results, or the build cache next to the default OUT), `.tar.gz`
  and `..tar.gz` OUT itself. Names that are not one plain path component are
  refused now, and nothing is removed unless its real path is strictly
  inside OUT. `make grade SUBMISSION=..` named its default OUT build/grade/..
- Whose row a grade lands in came from submission_metadata.json inside the
  student's own folder, which a student writes. It comes from the
  submission's name, or from the instructor's --roster, now.

The unit tests call the grader's functions; one real batch of hostile names
(submissions without chapters, so nothing compiles and the batch takes
seconds) runs in both isolation modes: bubblewrap, and the fallback without
namespaces (a `bwrap` on PATH that fails).
"""
import csv
import hashlib
import os
import shutil
import subprocess
import sys
import tarfile
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
GRADE = os.path.join(ROOT, 'tools', 'grading', 'grade.py')
sys.path.insert(0, ROOT)
from tools.grading import batch  # noqa: E402
sys.path.insert(0, HERE)
import test_grade as tg  # noqa: E402

# Names that are not one plain path component, or that are the batch's own
# files: (entry in the submissions directory, is it an archive).
HOSTILE = [('...tar.gz', True), ('..tar.gz', True), ('.tar.gz', True), ('.tgz', True),
           ('.hidden', False), ('-rf', False), ('with space', False),
           ('\u00fcn\u00efcode', False), ('new\nline', False), ('cache.zip', True),
           ('grades.csv.tgz', True), ('gradebook.csv', False), ('a..b.zip', True),
           ('=1+1.zip', True), ('alice\n', False)]
# Entries that are no submission at all: each gets a refused row too.
NOT_SUBMISSIONS = ['notes.txt', 'bob.ZIP', 'carol.zip']


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'w', encoding='utf-8') as f:
        f.write(text)


def empty_archive(path):
    with tarfile.open(path, 'w:gz'):
        pass


def not_submissions(subs, elsewhere):
    """NOT_SUBMISSIONS in subs: a text file, an archive whose suffix is not
    one the grader reads (names are case-sensitive), and a link to an archive
    in elsewhere (whose member names the batch must never show)."""
    write(os.path.join(subs, 'notes.txt'), 'not a submission')
    empty_archive(os.path.join(subs, 'bob.ZIP'))
    target = os.path.join(elsewhere, 'private.zip')
    empty_archive(target)
    os.symlink(target, os.path.join(subs, 'carol.zip'))


def snapshot(top, leave_out):
    """{path: sha256 or 'dir'} of everything under top but leave_out's tree."""
    found = {}
    for d, dirs, files in os.walk(top):
        dirs[:] = [x for x in dirs if os.path.join(d, x) != leave_out]
        for name in dirs:
            found[os.path.join(d, name)] = 'dir'
        for name in files:
            with open(os.path.join(d, name), 'rb') as f:
                found[os.path.join(d, name)] = hashlib.sha256(f.read()).hexdigest()
    return found


class NameTest(unittest.TestCase):
    def test_hostile_names_are_refused(self):
        for entry, archive in HOSTILE + [('..', False), ('.', False), ('', False),
                                         ('CACHE', False), ('x' * 101, False)]:
            name = batch.ARCHIVE_SUFFIX.sub('', entry) if archive else entry
            with self.subTest(name=name):
                self.assertIsNotNone(batch.name_problem(name))

    def test_plain_names_are_accepted(self):
        for name in ('alice', 'submission_123', 'Bob.Smith', 'x-1', '7'):
            self.assertIsNone(batch.name_problem(name), name)

    def test_every_entry_is_graded_or_refused(self):
        with tempfile.TemporaryDirectory() as tmp:
            for entry, archive in HOSTILE:
                if archive:
                    empty_archive(os.path.join(tmp, entry))
                else:
                    os.mkdir(os.path.join(tmp, entry))
            os.mkdir(os.path.join(tmp, 'alice'))
            os.mkdir(os.path.join(tmp, 'bob'))
            empty_archive(os.path.join(tmp, 'bob.zip'))
            with tempfile.TemporaryDirectory() as elsewhere:
                not_submissions(tmp, elsewhere)
                found = batch.submissions_in(tmp)
        problems = {os.path.basename(path): problem for _, path, problem in found}
        self.assertEqual({e for e, p in problems.items() if p is None}, {'alice'})
        for entry, _ in HOSTILE:
            self.assertTrue(problems[entry], entry)
        self.assertIn('another submission is also named bob', problems['bob'])
        self.assertIn('another submission is also named bob', problems['bob.zip'])
        self.assertIn('neither a directory nor', problems['notes.txt'])
        self.assertIn('neither a directory nor', problems['bob.ZIP'])
        self.assertIn('a link, not followed', problems['carol.zip'])

    def test_printable_escapes_control_characters(self):
        self.assertEqual(batch.printable('new\nline\x1b'), 'new\\nline\\x1b')


class RemoveInsideTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix='lrt-remove-test-')
        self.out = os.path.join(self.tmp, 'grade', 'batch')
        write(os.path.join(self.tmp, 'grade', 'cache', 'sentinel'), 'keep')
        write(os.path.join(self.out, 'other', 'results.json'), '{}')
        write(os.path.join(self.tmp, 'elsewhere', 'sentinel'), 'keep')

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def test_outside_or_the_output_itself_is_never_removed(self):
        os.symlink(os.path.join(self.tmp, 'elsewhere'), os.path.join(self.out, 'link'))
        for name in ('..', '.', '', '../cache', 'link', '../../elsewhere'):
            with self.subTest(name=name):
                with self.assertRaises(ValueError):
                    batch.remove_inside(self.out, os.path.join(self.out, name))
        for path in ('grade/cache/sentinel', 'grade/batch/other/results.json',
                     'elsewhere/sentinel'):
            self.assertTrue(os.path.exists(os.path.join(self.tmp, path)), path)

    def test_a_result_inside_is_removed(self):
        batch.remove_inside(self.out, os.path.join(self.out, 'other'))
        self.assertFalse(os.path.exists(os.path.join(self.out, 'other')))
        batch.remove_inside(self.out, os.path.join(self.out, 'not-there'))   # no error


class RosterTest(unittest.TestCase):
    def roster(self, text, names=('team1', 'alice')):
        with tempfile.NamedTemporaryFile('w', suffix='.csv', delete=False,
                                         encoding='utf-8') as f:
            f.write(text)
        self.addCleanup(os.remove, f.name)
        return f.name, (lambda: batch.read_roster(f.name, set(names)))

    def test_groups_and_single_students(self):
        _, read = self.roster('submission,student,login\nteam1,Ada Lovelace,ada@x\n'
                              '\nteam1,Alan Turing,alan@x\nalice,Alice,alice@x\n')
        self.assertEqual(read(), {'team1': [('Ada Lovelace', 'ada@x'),
                                            ('Alan Turing', 'alan@x')],
                                  'alice': [('Alice', 'alice@x')]})

    def test_mistakes_name_the_file_and_line(self):
        cases = [('', ':1: ', 'the first line must be the header'),
                 ('student,login\nalice,a\n', ':1: ', 'the first line must be the header'),
                 ('submission,student,login\nalice,Alice\n', ':2: ', 'expected 3 columns'),
                 ('submission,student,login\nalice,Alice,a,x\n', ':2: ',
                  'expected 3 columns'),
                 ('submission,student,login\nalice,,a\n', ':2: ', 'must all be given'),
                 ('submission,student,login\nalice,A,a\nghost,G,g\n', ':3: ',
                  "there is no submission named 'ghost'"),
                 ('submission,student,login\nalice,A,a\nteam1,B,a\n', ':3: ',
                  'login a is already on line 2'),
                 ('submission,student,login\nalice,"A\nB",a\n', ':2: ',
                  'control character')]
        for text, line, message in cases:
            with self.subTest(text=text):
                path, read = self.roster(text)
                with self.assertRaises(batch.RosterError) as caught:
                    read()
                self.assertIn(path + line, str(caught.exception))
                self.assertIn(message, str(caught.exception))

    def test_a_file_that_is_not_utf8(self):
        path, read = self.roster('')
        with open(path, 'wb') as f:
            f.write(b'submission,student,login\nalice,\xff,a\n')
        with self.assertRaises(batch.RosterError) as caught:
            read()
        self.assertIn(path + ': cannot be read', str(caught.exception))

    def test_metadata_inside_a_submission_is_ignored(self):
        with tempfile.TemporaryDirectory() as tmp:
            write(os.path.join(tmp, 'mallory', batch.METADATA),
                  '{"users": [{"name": "Victim", "email": "victim@x"}]}')
            who, note = batch.submitters('mallory', os.path.join(tmp, 'mallory'), None)
            self.assertEqual(who, [('mallory', 'mallory')])
            self.assertIn('submission_metadata.json was ignored', note)
            who, note = batch.submitters('mallory', os.path.join(tmp, 'mallory'),
                                         {'mallory': [('Mallory', 'mal@x')]})
            self.assertEqual(who, [('Mallory', 'mal@x')])


def kit_root(tmp):
    """A book whose build/ is scratch: this book's chapters, tests and tools."""
    root = os.path.join(tmp, 'book')
    os.mkdir(root)
    for name in ('chapters', 'tests', 'tools'):
        os.symlink(os.path.join(ROOT, name), os.path.join(root, name))
    return root


class SingleSubmissionOutTest(unittest.TestCase):
    """make grade SUBMISSION=... without OUT: the results go to
    build/grade/NAME, NAME from the submission's path."""

    def test_a_name_that_is_no_directory_of_its_own_is_refused(self):
        with tempfile.TemporaryDirectory() as tmp:
            root = kit_root(tmp)
            where = os.path.join(tmp, 'work', 'deeper')
            os.makedirs(where)
            empty_archive(os.path.join(where, '...tar.gz'))
            empty_archive(os.path.join(where, 'cache.tar.gz'))
            for submission in ('.', '..', '...tar.gz', 'cache.tar.gz'):
                with self.subTest(submission=submission):
                    proc = subprocess.run([sys.executable, GRADE, '--root', root,
                                           '--chapters', '05', '--quiet', submission],
                                          cwd=where, capture_output=True, text=True)
                    self.assertEqual(proc.returncode, 2, proc.stdout + proc.stderr)
                    self.assertIn('cannot name the results after %s' % submission,
                                  proc.stderr)
                    self.assertIn('give --out DIR', proc.stderr)
                    self.assertFalse(os.path.exists(os.path.join(root, 'build')))
            # A plain name goes where it always did.
            os.mkdir(os.path.join(where, 'alice'))
            proc = subprocess.run([sys.executable, GRADE, '--root', root, '--chapters', '05',
                                   '--quiet', 'alice'], cwd=where, capture_output=True,
                                  text=True)
            self.assertEqual(proc.returncode, 0, proc.stderr)
            self.assertEqual(os.listdir(os.path.join(root, 'build', 'grade')), ['alice'])


class HostileBatchTest(unittest.TestCase):
    """One real batch: the hostile names, a student's in-folder metadata that
    names another student, a group in the roster; the output next to a
    cache and another batch's results, as build/grade/batch is by default."""

    def batch(self, fallback):
        tmp = tempfile.mkdtemp(prefix='lrt-batch-names-')
        self.addCleanup(shutil.rmtree, tmp)
        subs = os.path.join(tmp, 'submissions')
        grade_dir = os.path.join(tmp, 'build', 'grade')
        out = os.path.join(grade_dir, 'batch')
        cache = os.path.join(grade_dir, 'cache')
        # Sentinels: in OUT's parent, in the cache, in OUT, next to the build.
        write(os.path.join(cache, 'sentinel'), 'the cache')
        write(os.path.join(grade_dir, 'other-batch', 'grades.csv'), 'another batch')
        write(os.path.join(tmp, 'build', 'sentinel'), 'the build')
        write(os.path.join(out, 'sentinel'), 'a file of OUT that is no result')
        write(os.path.join(out, 'alice', 'stale.txt'), 'an old result')   # removed
        for entry, archive in HOSTILE:
            if archive:
                os.makedirs(subs, exist_ok=True)
                empty_archive(os.path.join(subs, entry))
            else:
                os.makedirs(os.path.join(subs, entry))
        not_submissions(subs, tmp)
        for name in ('alice', 'team1', 'mallory'):
            write(os.path.join(subs, name, 'notes.txt'), 'no chapter here')
        # Links planted in OUT under the names that the batch's files had while
        # being written: a write through one would change a file outside OUT.
        write(os.path.join(tmp, 'victim.txt'), 'a file outside OUT')
        for planted in ('grades.csv.tmp', 'gradebook.csv.tmp'):
            os.symlink(os.path.join(tmp, 'victim.txt'), os.path.join(out, planted))
        write(os.path.join(subs, 'mallory', batch.METADATA),
              '{"users": [{"name": "Victim", "email": "victim@x", "id": 7}]}')
        roster = os.path.join(tmp, 'roster.csv')
        write(roster, 'submission,student,login\nteam1,Ada Lovelace,ada@x\n'
              'team1,Alan Turing,alan@x\n')
        env = dict(os.environ)
        if fallback:
            fake = tg.failing_bwrap(os.path.join(tmp, 'fake-bin'))
            env['PATH'] = fake + os.pathsep + env['PATH']
        mode = subprocess.run([sys.executable, '-c', 'from tools.grading import sandbox; print(sandbox.isolation())'],
                              cwd=ROOT, env=env, capture_output=True,
                              text=True, check=True).stdout.strip()
        before = snapshot(tmp, out)
        proc = subprocess.run([sys.executable, GRADE, '--batch', subs, '--out', out,
                               '--cache', cache, '--chapters', '05', '--roster', roster] +
                              (['--allow-no-sandbox'] if fallback else []),
                              cwd=ROOT, env=env, capture_output=True, text=True)
        return tmp, out, before, proc, mode

    def check(self, fallback):
        tmp, out, before, proc, mode = self.batch(fallback)
        self.assertEqual(mode, 'bubblewrap' if not fallback else
                         'unprivileged user' if os.geteuid() == 0 else 'none')
        self.assertEqual(proc.returncode, 0, proc.stdout + proc.stderr)
        # Nothing outside OUT changed; in OUT, only the results were written.
        self.assertEqual(snapshot(tmp, out), before)
        self.assertEqual(sorted(os.listdir(out)), ['alice', 'gradebook.csv', 'gradebook.csv.tmp',
                                                   'grades.csv', 'grades.csv.tmp', 'mallory',
                                                   'sentinel', 'team1'])
        self.assertFalse(os.path.exists(os.path.join(out, 'alice', 'stale.txt')))
        self.assertIn('graded 3 submissions', proc.stdout)
        refused_entries = [e for e, _ in HOSTILE] + NOT_SUBMISSIONS
        for entry in refused_entries:
            shown = batch.printable(entry)
            self.assertIn('grade-batch: REFUSED %s, not graded' % shown, proc.stderr)
            self.assertIn(shown, proc.stdout.split('REFUSED (not graded): ')[1])
        # The gradebook: a refused submission has a row with no number; the
        # roster's group a row per member; mallory's row is mallory's.
        with open(os.path.join(out, 'gradebook.csv'), newline='', encoding='utf-8') as f:
            rows = {(r[0], r[1]): r[3:] for r in list(csv.reader(f))[1:]}
        graded = {('alice', 'alice'), ('mallory', 'mallory'), ('Ada Lovelace', 'ada@x'),
                  ('Alan Turing', 'alan@x')}
        refused = {('REFUSED ' + batch.printable(e),) * 2 for e in refused_entries}
        self.assertEqual(set(rows), graded | refused)
        for who in graded:
            self.assertEqual(rows[who][-1], '0', who)
        for who in refused:
            self.assertEqual(set(rows[who]), {''}, who)
        self.assertIn('mallory: its submission_metadata.json was ignored', proc.stderr)
        with open(os.path.join(out, 'grades.csv'), newline='', encoding='utf-8') as f:
            points = [(r['student'], r['points']) for r in csv.DictReader(f)]
        for entry in refused_entries:
            self.assertIn(('REFUSED ' + batch.printable(entry), ''), points)
        # What the linked archive holds was never read.
        self.assertNotIn('private', proc.stdout + proc.stderr)

    def test_bubblewrap(self):
        self.check(fallback=False)

    def test_fallback_without_namespaces(self):
        self.check(fallback=True)

    def test_a_roster_mistake_stops_the_batch_before_it_starts(self):
        with tempfile.TemporaryDirectory() as tmp:
            os.makedirs(os.path.join(tmp, 'subs', 'alice'))
            roster = os.path.join(tmp, 'roster.csv')
            write(roster, 'submission,student,login\nalice,Alice,a\nghost,Ghost,g\n')
            out = os.path.join(tmp, 'out')
            proc = subprocess.run([sys.executable, GRADE, '--batch',
                                   os.path.join(tmp, 'subs'), '--out', out, '--roster',
                                   roster, '--chapters', '05'], cwd=ROOT,
                                  capture_output=True, text=True)
            self.assertEqual(proc.returncode, 2, proc.stdout + proc.stderr)
            self.assertIn("%s:3: there is no submission named 'ghost'" % roster, proc.stderr)
            self.assertFalse(os.path.exists(out))


if __name__ == '__main__':
    unittest.main()
