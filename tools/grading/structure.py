"""The structure of a student's chapter against the book's: exercise chunks
renamed, deleted or duplicated, code changed outside the solution regions
(check_structure), and the text graded for one exercise: the student's
regions spliced into the book's chapter, or the book's solutions of the
other exercises into the student's (exercise_text)."""
import difflib

from tools.exercises import markup

def parse_chapter(path):
    book = markup.Book([path], tests=False)
    return book.chapters[0], book


def skeleton(chunk, regions):
    """A chunk's body with each solution region (and stub block) replaced by
    one placeholder line; trailing blanks ignored."""
    out, i, by_begin = [], 0, {r.begin: r for r in regions}
    body = chunk.body
    while i < len(body):
        region = by_begin.get(i)
        if region is not None:
            out.append('\0REGION')
            i = (region.stub_end if region.stub_end is not None else region.end) + 1
            continue
        out.append(body[i].rstrip())
        i += 1
    while out and not out[-1]:
        out.pop()
    return tuple(out)


def chunk_regions(chunk):
    regions, errors = markup.find_regions(chunk.body)
    for region in regions:
        region.chunk = region.path = chunk
    return regions, errors


# A chapter can make a problem of every one of its lines (a solution region
# of fragment uses, a chunk per line): the messages listed per chapter are
# capped, and the rest counted, so that the feedback and the grader's memory
# stay small whatever the chapter holds.
MAX_LISTED = 20
MAX_MESSAGE = 400   # characters of one message (a chunk name can be long)


class Listed(list):
    """Messages: the first MAX_LISTED, each cut to MAX_MESSAGE characters,
    and the number of those left out (`more`)."""
    def __init__(self):
        super().__init__()
        self.more = 0

    def append(self, message):
        if len(self) < MAX_LISTED:
            super().append(message if len(message) <= MAX_MESSAGE else
                           message[:MAX_MESSAGE] + '... (%d characters)' % len(message))
        else:
            self.more += 1

    def closed(self, what):
        """The list, with a last line that counts what was left out."""
        if self.more:
            super().append('... and %d more %s' % (self.more, what))
        return list(self)


def check_structure(reference, student, student_name, allow=False):
    """Compares two parsed chapters. Returns (problems, code_changed, plan):
    problems are messages; plan maps each reference region to the student's
    region lines ((line, text) list) or None (deleted: use the stub).
    At most MAX_LISTED problems and changes are listed (see Listed)."""
    problems = Listed()
    not_done = '' if allow else ': graded as not done'
    exercise_chunks = {f: e for e in reference.exercises for f in e.fragments}
    ref_names = [c.name for c in reference.chunks]
    stu_names = [c.name for c in student.chunks]
    stu_regions = {}
    for chunk in student.chunks:
        regions, errors = chunk_regions(chunk)
        for index, message in errors:
            problems.append('%s:%d: in <<%s>>: %s' % (student_name, chunk.line + 1 + index,
                                                       chunk.name, message))
        stu_regions[id(chunk)] = regions
    stu_skeletons = {id(c): skeleton(c, stu_regions[id(c)]) for c in student.chunks}
    # A chapter may define any number of chunks the book does not have: the
    # names are looked up in sets, and each chunk's skeleton is made once, so
    # that the check stays linear in the chapter's length (a chapter of
    # 150,000 new chunks with its exercise chunks renamed took an hour).
    ref_name_set = set(ref_names)
    new_names = [n for n in dict.fromkeys(stu_names) if n not in ref_name_set]
    new_name_set = set(new_names)
    for name, exercise in exercise_chunks.items():
        want = ref_names.count(name)
        have = [c for c in student.chunks if c.name == name]
        if not have:
            guess = new_names[:MAX_LISTED]
            first = [c for c in reference.chunks if c.name == name][0]
            ref_skel = skeleton(first, [r for r in reference.regions if r.chunk is first])
            renamed = [c for c in student.chunks
                       if c.name in new_name_set and stu_skeletons[id(c)] == ref_skel]
            if renamed:
                problems.append('%s:%d: exercise chunk <<%s>> (%s) was renamed to <<%s>>%s'
                                % (student_name, renamed[0].line, name, exercise.id,
                                   renamed[0].name, not_done))
            else:
                problems.append('%s: exercise chunk <<%s>> (%s) was deleted%s%s'
                                % (student_name, name, exercise.id,
                                   ' or renamed (new chunks: %s)' % ', '.join(
                                       '<<%s>>' % g for g in guess) if guess else '',
                                   not_done))
        elif len(have) > want:
            problems.append('%s:%d: exercise chunk <<%s>> (%s) is defined %d times (lines '
                            '%s); the book defines it %d time(s)%s'
                            % (student_name, have[want].line, name, exercise.id, len(have),
                               ', '.join(str(c.line) for c in have), want,
                               '' if allow else ': only the first is graded'))
    # The code outside the solution regions, chunk by chunk.
    ref_seq = [(c.name, skeleton(c, [r for r in reference.regions if r.chunk is c]))
               for c in reference.chunks]
    stu_seq = [(c.name, stu_skeletons[id(c)]) for c in student.chunks]
    changes = Listed()
    matcher = difflib.SequenceMatcher(None, ref_seq, stu_seq, autojunk=False)
    for tag, i1, i2, j1, j2 in matcher.get_opcodes():
        if tag == 'equal':
            continue
        ref_part, stu_part = reference.chunks[i1:i2], student.chunks[j1:j2]
        stu_by_name = {}
        for c in stu_part:
            stu_by_name.setdefault(c.name, []).append(c)
        for c in ref_part:
            same = stu_by_name.get(c.name)
            if same:
                s = same.pop(0)
                changes.append('%s:%d: the code of <<%s>> differs from the book\'s '
                               '(outside the solution regions)' % (student_name, s.line,
                                                                   c.name))
            else:
                changes.append('%s: chunk <<%s>> (book line %d) is missing'
                               % (student_name, c.name, c.line))
        for name, rest in stu_by_name.items():
            for s in rest:
                changes.append('%s:%d: chunk <<%s>> is %s' % (
                    student_name, s.line, name, 'an extra definition' if name in ref_name_set
                    else 'not in the book'))
    # Which student region fills which reference region: the k-th region of
    # chunk name X in the student's text fills the k-th of the reference's.
    plan = {}
    for name in dict.fromkeys(ref_names):
        ref_r = [r for r in reference.regions if r.chunk.name == name]
        stu_r = [r for c in student.chunks if c.name == name for r in stu_regions[id(c)]]
        for k, region in enumerate(ref_r):
            if k < len(stu_r):
                s = stu_r[k]
                plan[id(region)] = [(s.line(i), s.chunk.body[i])
                                    for i in range(s.begin + 1, s.end)]
            else:
                plan[id(region)] = None
                if name not in exercise_chunks or [c for c in student.chunks
                                                   if c.name == name]:
                    problems.append('%s: the solution region %d of <<%s>> is missing '
                                    '(BEGIN/END SOLUTION markers removed?): graded as '
                                    'not done' % (student_name, k + 1, name))
        if len(stu_r) > len(ref_r):
            extra = stu_r[len(ref_r)]
            problems.append('%s:%d: <<%s>> has %d solution regions; the book has %d: the '
                            'extra ones are not graded' % (student_name,
                                                           extra.line(extra.begin),
                                                           name, len(stu_r), len(ref_r)))
    return problems.closed('problems'), changes.closed('changes'), plan


def compose(base, base_name, fills):
    """The chapter `base` (parsed) with some of its solution regions filled
    anew: fills maps a region of base to the lines (file, line, text) to put
    between its markers; other regions stay as they are. A filled region's
    stub block is dropped. Returns (text, line map: output line -> (file, line))."""
    starts = {r.line(r.begin): r for r in base.regions if r in fills}
    lines, where = [], []
    n = 1
    while n <= len(base.lines):
        region = starts.get(n)
        if region is None:
            lines.append(base.lines[n - 1])
            where.append((base_name, n))
            n += 1
            continue
        lines.append(base.lines[n - 1])        # // BEGIN SOLUTION
        where.append((base_name, n))
        for name, line, text in fills[region]:
            lines.append(text)
            where.append((name, line))
        end = region.line(region.end)
        lines.append(base.lines[end - 1])      # // END SOLUTION
        where.append((base_name, end))
        n = (region.line(region.stub_end) if region.stub_end is not None else end) + 1
    return '\n'.join(lines) + '\n', where


def exercise_text(reference, student, plan, exercise, student_name, allow):
    """Chapter text for grading `exercise` alone: the student's code for its
    regions, the book's solutions for every other exercise's. By default the
    book's text is the base (code the student changed outside the regions is
    not used); with `allow` (--allow-changes-outside-exercises), the
    student's. A region the student deleted gets the stub."""
    mine = set(exercise.fragments)
    if not allow:
        fills = {}
        for region in reference.regions:
            if region.chunk.name not in mine:
                continue
            filled = plan.get(id(region))
            if filled is None:
                fills[region] = [(reference.path + ' (stub)', region.line(region.begin), t)
                                 for t in markup.stub_code(region)]
            else:
                fills[region] = [(student_name, line, t) for line, t in filled]
        return compose(reference, reference.path, fills)
    # The student's chapter, with the k-th region of each chunk name that
    # belongs to another exercise replaced by the book's k-th.
    fills, seen = {}, {}
    for region in student.regions:
        name = region.chunk.name
        k = seen.get(name, 0)
        seen[name] = k + 1
        if name in mine:
            continue
        ref = [r for r in reference.regions if r.chunk.name == name]
        if k < len(ref):
            fills[region] = [(reference.path, line, t) for line, t in ref[k].solution]
    return compose(student, student_name, fills)

