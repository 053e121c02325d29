"""The builds of grading (docs/grading.md): the judge of a chapter, from the
book's code only, and the worker of one exercise, from the student's code.

    judge(cache, root, number)                 -> path of the judge binary
    Worker build: WorkerBuild(cache, root, number).build(chapter_dir, label)

The judge is the chapter's public and hidden tests compiled with LRT_JUDGE
(tests/calls/calls.h) and linked with the book's code as of the chapter; it
never contains a student's line, so it is built outside the sandbox, once,
and cached by its sources.

A worker is tests/calls/worker.cpp with the chapter's exercise calls, linked
with the code tangled from a directory of chapters (the book's, with the
student's text for one exercise). It is compiled inside the sandbox
(tools/sandbox.py): the compiler sees the tangled code and the public call
sources, nothing of the grader, so an `#include` of a hidden file finds
nothing. It is linked statically, so that the sandbox it runs in can be empty.
Only the library's translation units that the chapter's calls need are
compiled (the book's worker tells which); if the student's code needs more,
the link says so and the rest is compiled too.

Workers are cached by their tangled code (without #line directives) and
flags: submissions whose code is the same share one build. With ccache
installed, translation units that equal an earlier build's are not compiled
again. A worker that does not compile is tangled again with #line
directives, so that the errors name the chapters' lines.
"""
import concurrent.futures
import fcntl
import glob
import hashlib
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import sandbox  # noqa: E402

JUDGE_CXXFLAGS = ['-std=c++17', '-O2', '-ffp-contract=off', '-w']
WORKER_CXXFLAGS = ['-std=c++17', '-O0', '-ffp-contract=off', '-Wall', '-Wextra']
CALL_SOURCES = ['tests/calls/core.h', 'tests/calls/calls.h', 'tests/calls/worker.cpp']


class BuildError(Exception):
    """A build that failed; .output holds the compiler's words."""
    def __init__(self, output):
        super().__init__('build failed')
        self.output = output


def run(cmd, cwd=None, timeout=900):
    try:
        proc = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True,
                              errors='replace', timeout=timeout,
                              stdin=subprocess.DEVNULL)
        return proc.returncode, proc.stdout + proc.stderr
    except subprocess.TimeoutExpired as e:
        out = e.stdout or b''
        if isinstance(out, bytes):
            out = out.decode(errors='replace')
        return 'timeout', out + '\n(the build took longer than %d s)' % timeout


def tangle(root, chapters_dir, chapters, out, line_directives=False):
    """Tangles `chapters` (paths relative to chapters_dir's parent) into out."""
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    cmd = [sys.executable, os.path.join(root, 'tools', 'tangle.py'), '--out', out]
    if line_directives:
        cmd.append('--line-directives')
    code, output = run(cmd + chapters, cwd=os.path.dirname(chapters_dir))
    if code != 0:
        raise BuildError(output)


def tree_hash(directory, extra=''):
    """A hash of a tangled tree's files, #line directives left out (prose
    edits move them without changing the code)."""
    h = hashlib.sha256(extra.encode())
    for top, dirs, files in os.walk(directory):
        dirs.sort()
        for name in sorted(files):
            path = os.path.join(top, name)
            h.update(os.path.relpath(path, directory).encode() + b'\0')
            with open(path, 'rb') as f:
                for line in f:
                    if not line.startswith(b'#line '):
                        h.update(line)
            h.update(b'\0')
    return h.hexdigest()[:32]


def files_hash(root, patterns):
    h = hashlib.sha256()
    for pattern in patterns:
        for path in sorted(glob.glob(os.path.join(root, pattern))):
            h.update(os.path.relpath(path, root).encode() + b'\0')
            with open(path, 'rb') as f:
                h.update(f.read())
    return h.hexdigest()


def library_sources(src):
    return sorted(os.path.relpath(p, src) for p in glob.glob(
        os.path.join(src, 'lrt', '**', '*.cpp'), recursive=True))


class Locked:
    """An exclusive lock on a cache entry, so that parallel graders build it
    once."""
    def __init__(self, path):
        self.path = path + '.lock'

    def __enter__(self):
        self.file = open(self.path, 'w')
        fcntl.flock(self.file, fcntl.LOCK_EX)
        return self

    def __exit__(self, *exc):
        self.file.close()


def compile_all(jobs, commands):
    """Runs (argv, cwd) compile commands, `jobs` at a time; returns the
    output of the first that failed, or None."""
    with concurrent.futures.ThreadPoolExecutor(max(1, jobs)) as pool:
        results = list(pool.map(lambda c: run(c[0], cwd=c[1]), commands))
    for code, output in results:
        if code != 0:
            return output
    return None


def reference_chapters(root, number):
    chapters = sorted(glob.glob(os.path.join(root, 'chapters', '[0-9][0-9]-*.md')))
    return [p for p in chapters if os.path.basename(p)[:2] <= number]


# ---------------------------------------------------------------------------
# The judge

def judge(cache, root, number, jobs=2):
    """The judge of chapter `number`, built from the book's code (cached)."""
    chapters = reference_chapters(root, number)
    tests = ['tests/ch%s/*' % number, 'tests/hidden/ch%s/*' % number, 'tests/calls/*']
    key = hashlib.sha256((files_hash(root, [os.path.relpath(p, root) for p in chapters]) +
                          files_hash(root, tests + ['tools/tangle.py',
                                                    'tools/exercise_filter.py']) +
                          ' '.join(JUDGE_CXXFLAGS)).encode()).hexdigest()[:32]
    entry = os.path.join(cache, 'judge-%s-%s' % (number, key))
    binary = os.path.join(entry, 'judge')
    os.makedirs(cache, exist_ok=True)
    with Locked(entry):
        if os.path.isfile(binary):
            return binary
        work = tempfile.mkdtemp(prefix='judge-', dir=cache)
        try:
            src = os.path.join(work, 'src')
            tangle(root, os.path.join(root, 'chapters'),
                   [os.path.relpath(p, root) for p in chapters], src)
            # Test sources are named relative to the root, as their failure
            # messages show them.
            sources = [os.path.join(src, s) for s in library_sources(src)]
            for pattern in ('tests/ch%s/*.cpp' % number, 'tests/hidden/ch%s/*.cpp' % number):
                sources += sorted(os.path.relpath(p, root)
                                  for p in glob.glob(os.path.join(root, pattern)))
            sources.append('tests/calls/judge.cpp')
            objects, commands = [], []
            for i, source in enumerate(sources):
                obj = os.path.join(work, 'obj%03d.o' % i)
                objects.append(obj)
                commands.append((['g++'] + JUDGE_CXXFLAGS + ['-DLRT_JUDGE', '-I', src, '-I',
                                  'tests', '-c', source, '-o', obj], root))
            failed = compile_all(jobs, commands)
            if failed is None:
                code, failed = run(['g++', '-o', os.path.join(work, 'judge')] + objects +
                                   ['-lgtest', '-pthread'])
                failed = failed if code != 0 else None
            if failed is not None:
                raise BuildError('the judge of chapter %s (the book\'s own code and tests) '
                                 'does not build:\n%s' % (number, failed[-4000:]))
            # The judge holds the hidden tests: for the grader's eyes only.
            os.makedirs(entry, mode=0o700, exist_ok=True)
            os.chmod(entry, 0o700)
            os.replace(os.path.join(work, 'judge'), binary)
            return binary
        finally:
            shutil.rmtree(work, ignore_errors=True)


# ---------------------------------------------------------------------------
# Workers

class WorkerBuild:
    """Builds workers of chapter `number` from directories of chapters."""

    def __init__(self, cache, root, number, cxxflags=None, jobs=2):
        self.cache, self.root, self.number = cache, root, number
        self.cxxflags = cxxflags or WORKER_CXXFLAGS
        self.jobs = jobs
        self.ccache = os.path.join(cache, 'ccache') if shutil.which('ccache') else None
        self.calls_header = 'ch%s/exercise_calls.h' % number
        self.call_files = CALL_SOURCES + ['tests/' + self.calls_header]
        self._needed = None      # the set needed() found, once it has

    def build(self, chapters_dir, chapters, label):
        """The worker for the chapters (file names in chapters_dir), or a
        BuildError whose output names the chapters' lines."""
        work = tempfile.mkdtemp(prefix='worker-', dir=self.cache)
        try:
            src = os.path.join(work, 'src')
            tangle(self.root, chapters_dir, ['chapters/' + c for c in chapters], src)
            key = tree_hash(src, ' '.join(self.cxxflags) + '\0' +
                            files_hash(self.root, self.call_files))
            entry = os.path.join(self.cache, 'worker-%s-%s' % (self.number, key))
            binary = os.path.join(entry, 'worker')
            with Locked(entry):
                if os.path.isfile(binary):
                    return binary
                failure = self._compile(work)
                if failure is not None:
                    # Again with #line directives, for errors at the chapters' lines.
                    tangle(self.root, chapters_dir, ['chapters/' + c for c in chapters],
                           src, line_directives=True)
                    failure = self._compile(work) or failure
                    raise BuildError(failure)
                os.makedirs(entry, exist_ok=True)
                os.replace(os.path.join(work, 'worker'), binary)
                return binary
        finally:
            shutil.rmtree(work, ignore_errors=True)

    def _prepare(self, work):
        for rel in self.call_files:
            target = os.path.join(work, rel)
            os.makedirs(os.path.dirname(target), exist_ok=True)
            shutil.copy(os.path.join(self.root, rel), target)
        os.makedirs(os.path.join(work, 'obj'), exist_ok=True)

    def _command(self, work, argv):
        wrapped = sandbox.compile_command(argv, work, self.ccache)
        if wrapped is None:
            return (argv, work)
        if self.ccache:
            os.makedirs(self.ccache, exist_ok=True)
        return (wrapped, None)

    def _cxx(self):
        return (['ccache'] if self.ccache else []) + ['g++'] + self.cxxflags + [
            '-Isrc', '-Itests']

    def _compile(self, work, sources=None):
        """Compiles the worker in `work` (src/ tangled); None, or the errors."""
        self._prepare(work)
        all_sources = library_sources(os.path.join(work, 'src'))
        needed = self.needed() if sources is None else sources
        todo = [s for s in all_sources if s in needed]
        commands = [self._command(work, self._cxx() + [
            '-DLRT_WORKER', '-DLRT_CALLS_HEADER="%s"' % self.calls_header,
            '-c', 'tests/calls/worker.cpp', '-o', 'obj/worker.o'])]
        for s in todo:
            commands.append(self._command(work, self._cxx() + [
                '-c', 'src/' + s, '-o', 'obj/' + s.replace('/', '_') + '.o']))
        failed = compile_all(self.jobs, commands)
        if failed is not None:
            return failed
        for attempt in (0, 1):
            objects = ['obj/worker.o'] + ['obj/' + s.replace('/', '_') + '.o' for s in todo]
            argv = ['g++', '-static', '-o', 'worker'] + objects + ['-pthread']
            code, output = run(*self._command(work, argv))
            if code == 0:
                return None
            rest = [s for s in all_sources if s not in todo]
            if attempt or not rest or 'undefined reference' not in output:
                return output
            # The student's code calls into more of the library than the
            # book's does: compile the rest too.
            failed = compile_all(self.jobs, [self._command(work, self._cxx() + [
                '-c', 'src/' + s, '-o', 'obj/' + s.replace('/', '_') + '.o']) for s in rest])
            if failed is not None:
                return failed
            todo = all_sources
        return None

    def needed(self):
        """The library's sources that the book's worker links: the calls of
        the chapter reach only those."""
        if self._needed is not None:
            return self._needed
        key = hashlib.sha256((files_hash(self.root, [
            os.path.relpath(p, self.root) for p in reference_chapters(self.root, self.number)]) +
            files_hash(self.root, self.call_files) + ' '.join(self.cxxflags)).encode()
        ).hexdigest()[:32]
        record = os.path.join(self.cache, 'needed-%s-%s' % (self.number, key))
        with Locked(record):
            if os.path.isfile(record):
                with open(record) as f:
                    self._needed = set(f.read().split())
                return self._needed
            work = tempfile.mkdtemp(prefix='needed-', dir=self.cache)
            try:
                src = os.path.join(work, 'src')
                tangle(self.root, os.path.join(self.root, 'chapters'),
                       [os.path.relpath(p, self.root)
                        for p in reference_chapters(self.root, self.number)], src)
                self._prepare(work)
                sources = library_sources(src)
                if self._compile(work, sources=sources) is not None:
                    raise BuildError('the book\'s worker of chapter %s does not build'
                                     % self.number)
                # Link again, as an archive, and ask the linker which members
                # it took.
                objects = ['obj/' + s.replace('/', '_') + '.o' for s in sources]
                code, out = run(['ar', 'rcs', 'lib.a'] + objects, cwd=work)
                code, out = run(['g++', '-static', '-o', 'probe', 'obj/worker.o', 'lib.a',
                                 '-pthread', '-Wl,--trace'], cwd=work)
                taken = set(re.findall(r'lib\.a\((\S+?)\.o\)', out))
                self._needed = {s for s in sources if s.replace('/', '_') in taken}
                with open(record, 'w') as f:
                    f.write('\n'.join(sorted(self._needed)) + '\n')
            finally:
                shutil.rmtree(work, ignore_errors=True)
        return self._needed
