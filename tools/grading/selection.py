"""What a grading grades: the reference book (load_book), the chapters
(graded_chapters: --chapters, else a kit's, else every chapter with
exercises) and the exercises with their points (graded_exercises: a course
plan's assignment, else the chapters'), and an exercise's hint
(hint_text)."""
import json
import os
import re

from tools.exercises import course
from tools.exercises import markup
from tools.grading.submission import CHAPTER_NAME


def hint_text(exercise, lines):
    if exercise.hint is None:
        return ''
    kind, n = exercise.hint
    if kind == 'attribute':
        parsed = markup.parse_attributes(
            re.sub(r'^:+\s*\{|\}\s*$', '', lines[exercise.line - 1].strip()))
        return (parsed[2].get('hint', '') if parsed else '').strip()
    out = []
    for text in lines[n:]:
        if re.match(r'^:{3,}\s*$', text):
            break
        out.append(text.strip())
    return ' '.join(t for t in out if t)


def load_book(root):
    """The reference book: (chapter paths relative to root, markup.Book)."""
    ref_paths = sorted(os.path.join('chapters', f) for f in os.listdir(
        os.path.join(root, 'chapters')) if CHAPTER_NAME.match(f))
    cwd = os.getcwd()
    os.chdir(root)
    try:
        book = markup.load(ref_paths, root=root)
    finally:
        os.chdir(cwd)
    if book.errors:
        raise SystemExit('grade: the reference book has exercise errors:\n' +
                         '\n'.join(book.errors))
    return ref_paths, book


def graded_chapters(book, requested, root):
    """The numbers of the chapters to grade: those requested (--chapters), else
    the chapters a kit was built for (its exercises.json), else every chapter
    with exercises. A requested chapter must exist and have exercises."""
    with_exercises = [c.number for c in book.chapters if c.exercises]
    if requested:
        numbers = [c.number for c in book.chapters]
        chosen = []
        for word in re.split(r'[\s,]+', ' '.join(requested).strip()):
            match = re.match(r'^(?:.*/)?(\d{1,2})(?:-[^/]*\.md)?$', word)
            if not match:
                raise SystemExit('grade: --chapters names chapters by number ("02 05"), '
                                 'not %r' % word)
            number = '%02d' % int(match.group(1))
            if number not in numbers:
                raise SystemExit('grade: there is no chapter %s (chapters: %s)'
                                 % (number, ' '.join(numbers)))
            if number not in with_exercises:
                raise SystemExit('grade: chapter %s has no exercises (chapters with '
                                 'exercises: %s)' % (number, ' '.join(with_exercises)))
            chosen.append(number)
        return sorted(set(chosen))
    manifest = os.path.join(root, 'exercises.json')
    if os.path.isfile(manifest):
        try:
            with open(manifest, encoding='utf-8') as f:
                kit = json.load(f)['chosen_chapters']
        except (OSError, ValueError, KeyError, TypeError) as e:
            raise SystemExit('grade: %s cannot be read (%s): give --chapters'
                             % (manifest, e))
        return [n for n in with_exercises if n in kit]
    return with_exercises


def graded_exercises(book, args, root):
    """{exercise id: points} of what is graded: the exercises of --assignment
    in --plan, with the plan's points; else those of graded_chapters()."""
    if args.plan:
        if args.chapters:
            raise SystemExit('grade: give --chapters or --plan, not both')
        if not args.assignment:
            raise SystemExit('grade: --plan needs --assignment NAME')
        try:
            plan = course.load(args.plan, {e.id: e.points for e in book.exercises})
            return dict(plan.assignment(args.assignment).points)
        except course.PlanError as e:
            raise SystemExit('grade: %s' % e)
    if args.assignment:
        raise SystemExit('grade: --assignment needs --plan FILE')
    if not args.chapters:
        manifest = os.path.join(root, 'exercises.json')
        try:
            with open(manifest, encoding='utf-8') as f:
                kit = json.load(f)
        except OSError:
            kit = {}
        except ValueError as e:
            raise SystemExit('grade: %s cannot be read (%s): give --chapters'
                             % (manifest, e))
        if isinstance(kit, dict) and kit.get('assignment'):
            # The kit of an assignment of a plan: its exercises and points.
            return {e['id']: e['points'] for e in kit['exercises']}
    numbers = graded_chapters(book, args.chapters, root)
    return {e.id: e.points for c in book.chapters if c.number in numbers
            for e in c.exercises}

