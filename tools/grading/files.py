"""How the grader writes its files: whole or not at all (replacing,
atomic_write), or for its own user's eyes only (write_private).

A reader of the grader's outputs (Gradescope reading results.json while a
grading goes on, a grader in another process taking a worker from the
cache) must never find half a file, so every output is written beside its
place and renamed over it."""
import contextlib
import os
import tempfile


@contextlib.contextmanager
def replacing(path, mode=0o644, binary=False):
    """Yields a file to write that, when the block ends without an error,
    gets `mode` and is renamed over path; on an error it is removed and path
    is left as it was. The file is new, with a random name beside path, and
    created exclusively: no link planted in the directory under a name
    guessed in advance can turn the write to a file elsewhere."""
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(path) or '.',
                               prefix='.' + os.path.basename(path) + '.')
    try:
        with (os.fdopen(fd, 'wb') if binary else
              os.fdopen(fd, 'w', encoding='utf-8', newline='')) as f:
            yield f
        os.chmod(tmp, mode)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def atomic_write(path, text):
    """Writes text to path whole or not at all (replacing)."""
    with replacing(path) as f:
        f.write(text)


def write_private(path, text):
    """Writes text to a new file at path that only this user may read (a
    secret: a file of that name already there is an error, not followed)."""
    with open(os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600), 'w') as f:
        f.write(text)
