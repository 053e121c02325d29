"""Reading a student's submission: a directory, a .tar.gz/.tgz or a .zip
holding edited chapter files (chapters/NN-slug.md, or NN-slug.md anywhere
in it). Archives are read member by member into memory: no member is ever
written to disk, links and special files are ignored, and sizes are
limited. What is not a chapter of the book is ignored and said."""
import os
import re
import tarfile
import zipfile

CHAPTER_NAME = re.compile(r'^(\d\d)-[^/\\]*\.md$')
MAX_FILES = 2000              # members looked at in a submission
MAX_CHAPTER_BYTES = 4 << 20   # one chapter file
MAX_TOTAL_BYTES = 64 << 20    # everything read from a submission
MAX_NAME = 512                # characters of a member's name that is used
MAX_NAMES_BYTES = 1 << 20     # the names of all members, read
SHOWN_NAME = 200              # characters of an ignored name that are shown
TOO_MANY = ('more than %d files, or names longer than %d bytes in all: the rest is ignored'
            % (MAX_FILES, MAX_NAMES_BYTES))

class Submission:
    """The chapter files found in a submission, and what was ignored."""
    def __init__(self):
        self.chapters = {}    # basename -> (name inside the submission, bytes)
        self.ignored = []     # (name, reason)
        self.problems = []    # messages about the submission as a whole


# The characters of a name that is used, and so shown as it is, in and out
# of `...`: none that Markdown or HTML read as markup (<, [, *, !, `, ...).
SHOWABLE = re.compile(r"[\w .,+@=~()/'-]*")


def showable(name):
    """Whether a name can stand in the feedback as it is."""
    return SHOWABLE.fullmatch(name) is not None


def printable(name):
    """A file name as it can be shown on one line (control characters escaped)."""
    return ''.join(c if c.isprintable() else c.encode('unicode_escape').decode('ascii')
                   for c in name)


def shown(name):
    """A member's name as the feedback may show it inside `...`: on one
    line, without backticks, short; the submission chose it, and a name can
    be a megabyte of Markdown."""
    text = printable(name[:SHOWN_NAME].replace('`', "'"))
    if len(name) <= SHOWN_NAME and len(text) <= SHOWN_NAME:
        return text
    return text[:SHOWN_NAME] + '... (%d characters)' % len(name)


def safe_name(name):
    """A member name as a relative path, or None if it escapes."""
    name = name.replace('\\', '/')
    if name.startswith('/') or re.match(r'^[A-Za-z]:', name):
        return None
    parts = [p for p in name.split('/') if p not in ('', '.')]
    if not parts or '..' in parts:
        return None
    return '/'.join(parts)


def read_submission(path, reference_names):
    """Reads a submission without writing any of it to disk outside memory."""
    sub = Submission()
    entries = []   # (name, reader() -> bytes, size)  regular files only
    total = 0

    def consider(name, size, reader):
        nonlocal total
        if len(name) > MAX_NAME or not showable(name):
            sub.ignored.append((shown(name), 'a name of more than %d characters, or with '
                                'characters other than letters, digits, spaces and '
                                ". , + @ = ~ ( ) / ' - _: ignored" % MAX_NAME))
            return
        clean = safe_name(name)
        if clean is None:
            sub.ignored.append((name, 'unsafe path (absolute or with ..): ignored'))
            return
        base = clean.rsplit('/', 1)[-1]
        if not CHAPTER_NAME.match(base):
            sub.ignored.append((clean, 'not a chapter file'))
            return
        if base not in reference_names:
            sub.ignored.append((clean, 'no chapter of the book is named %s' % base))
            return
        if size > MAX_CHAPTER_BYTES:
            sub.ignored.append((clean, 'too large (%d bytes)' % size))
            return
        if total + size > MAX_TOTAL_BYTES:
            sub.ignored.append((clean, 'the submission is too large'))
            return
        try:
            data = reader()
        except (ValueError, OSError, EOFError, zipfile.BadZipFile, tarfile.TarError,
                RuntimeError) as e:
            sub.ignored.append((clean, 'cannot be read (%s)' % e))
            return
        total += len(data)
        entries.append((clean, data))

    def reader_of(read):
        def get():
            data = read()
            if len(data) > MAX_CHAPTER_BYTES:
                raise ValueError('too large')
            return data
        return get

    if os.path.isdir(path):
        count = names = 0
        for top, dirs, files in os.walk(path, followlinks=False):
            # Every entry counts, directories and links too, and the walk
            # ends at the first that goes over.
            count += len(dirs) + len(files)
            names += sum(len(n) for n in dirs + files)
            if count > MAX_FILES or names > MAX_NAMES_BYTES:
                sub.problems.append(TOO_MANY)
                break
            dirs.sort()
            for d in list(dirs):
                if os.path.islink(os.path.join(top, d)):
                    sub.ignored.append((shown(os.path.relpath(os.path.join(top, d), path)),
                                        'a symbolic link: ignored'))
                    dirs.remove(d)
            for f in sorted(files):
                full = os.path.join(top, f)
                rel = os.path.relpath(full, path)
                if os.path.islink(full) or not os.path.isfile(full):
                    sub.ignored.append((shown(rel), 'not a regular file (a link?): ignored'))
                    continue

                def read(full=full):
                    with open(full, 'rb') as fh:
                        return fh.read(MAX_CHAPTER_BYTES + 1)
                consider(rel, os.path.getsize(full), reader_of(read))
    elif zipfile.is_zipfile(path):
        try:
            with zipfile.ZipFile(path) as z:
                names = 0
                for count, info in enumerate(z.infolist()):
                    names += len(info.filename)
                    if count >= MAX_FILES or names > MAX_NAMES_BYTES:
                        sub.problems.append(TOO_MANY)
                        break
                    if info.is_dir():
                        continue
                    mode = (info.external_attr >> 16) & 0o170000
                    if mode and mode != 0o100000:
                        sub.ignored.append((shown(info.filename), 'not a regular file (a link?): '
                                            'ignored'))
                        continue
                    consider(info.filename, info.file_size, reader_of(
                        lambda info=info: z.open(info).read(MAX_CHAPTER_BYTES + 1)))
        except (zipfile.BadZipFile, OSError, EOFError, RuntimeError) as e:
            sub.problems.append('the archive is damaged: %s' % e)
    elif tarfile.is_tarfile(path):
        try:
            with tarfile.open(path) as t:
                names = 0
                for count, member in enumerate(t):
                    names += len(member.name) + len(member.linkname)
                    if count >= MAX_FILES or names > MAX_NAMES_BYTES:
                        sub.problems.append(TOO_MANY)
                        break
                    if member.isdir():
                        continue
                    if not member.isfile():
                        sub.ignored.append((shown(member.name), 'not a regular file (a '
                                            'link?): ignored'))
                        continue
                    consider(member.name, member.size, reader_of(
                        lambda m=member: t.extractfile(m).read(MAX_CHAPTER_BYTES + 1)))
        except (tarfile.TarError, OSError, EOFError) as e:
            sub.problems.append('the archive is damaged: %s' % e)
    else:
        sub.problems.append('%s is neither a directory nor a .tar.gz or .zip archive'
                            % os.path.basename(path))
    # One file per chapter: chapters/NN-slug.md first, then the shortest path.
    by_base = {}
    for name, data in entries:
        by_base.setdefault(name.rsplit('/', 1)[-1], []).append((name, data))
    for base, found in sorted(by_base.items()):
        found.sort(key=lambda e: (not (e[0] == 'chapters/' + base or
                                       e[0].endswith('/chapters/' + base)),
                                  e[0].count('/'), e[0]))
        name, data = found[0]
        sub.chapters[base] = (name, data)
        for other, _ in found[1:]:
            sub.ignored.append((other, 'another copy of %s; graded %s' % (base, name)))
    return sub

