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
student's text for one exercise), and with tests/calls/wall.cpp, its entry
point, which installs the worker's system-call filter before anything else
runs. It is compiled inside the sandbox
(tools/grading/sandbox.py): the compiler sees the tangled code and the public call
sources, nothing of the grader, so an `#include` of a hidden file finds
nothing. It is linked statically, so that the sandbox it runs in can be empty.
Only the library's translation units that the chapter's calls need are
compiled (the book's worker tells which); if the student's code needs more,
the link says so and the rest is compiled too.

Workers are cached by every byte of their tangled code (tangled without
#line directives, so that prose edits do not move the code) and flags: submissions whose code is the same share one build. With ccache
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
import signal
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
from tools.compile import flags as compile_flags  # noqa: E402
from tools.grading import sandbox  # noqa: E402
from tools.grading.files import replacing  # noqa: E402

# The compiler and the flags of the judge and of a worker: tools/compile/flags.mk
# says which and why, for every compile of the book's code.
CXX = compile_flags.value('CXX')
JUDGE_CXXFLAGS = compile_flags.words('JUDGE_CXXFLAGS')
WORKER_CXXFLAGS = compile_flags.words('WORKER_CXXFLAGS')
# The tools that shape a tangle (tools/noweb/tangle.py runs the two filters, and
# markup_filter.py follows tools/exercises/regions.py's markers in the chunks
# of tools/noweb/chunks.py): inputs of every build from tangled code, so part of its key.
TANGLE_TOOLS = ['tools/noweb/tangle.py', 'tools/noweb/markup_filter.py', 'tools/noweb/fragment_comments.py',
                'tools/exercises/markup.py', 'tools/exercises/regions.py', 'tools/noweb/chunks.py']
# MB of one file that a worker's build may write: the book's workers are
# about 3 MB, their objects less.
BUILD_FILE_MB = 64
CALL_SOURCES = ['tests/calls/' + name for name in (
    'core.h', 'calls.h', 'encoding.h', 'reply.h', 'kept.h', 'memory_files.h', 'rpc.h',
    'exercise_test.h', 'framing.h', 'worker.cpp', 'wall.cpp')]
# The worker's entry point: tests/calls/wall.cpp's routine that installs the
# system-call filter before the C library, or any of the student's code, runs
# (the student's code can run at static-initialization time), then jumps to
# the C library's _start.
WALL_LINK = ['obj/wall.o', '-Wl,-e,lrt_wall_entry',
             # files that calls give in memory (tests/calls/worker.cpp)
             '-Wl,--wrap=fopen']


class BuildError(Exception):
    """A build that failed; .output holds the compiler's words."""
    def __init__(self, output):
        super().__init__('build failed')
        self.output = output


# Bytes of a command's output that run() keeps: its first half and its last
# (a compiler's first errors, a program's last words). A compile of a
# student's code may print without end.
MAX_OUTPUT = 256 << 10


class Output:
    """A pipe's bytes as run() keeps them: the head, and a tail that rolls."""
    def __init__(self):
        self.head, self.tail, self.dropped = b'', b'', 0

    def add(self, data):
        room = MAX_OUTPUT // 2 - len(self.head)
        self.head += data[:max(room, 0)]
        self.tail += data[max(room, 0):]
        excess = len(self.tail) - MAX_OUTPUT // 2
        if excess > 0:
            self.dropped += excess
            self.tail = self.tail[excess:]

    def text(self):
        cut = '\n[... %d bytes of output left out ...]\n' % self.dropped if self.dropped else ''
        return (self.head.decode(errors='replace') + cut +
                self.tail.decode(errors='replace'))


def run(cmd, cwd=None, timeout=900):
    """Runs cmd, its output (stdout and stderr) kept up to MAX_OUTPUT bytes;
    (exit status, output), or ('timeout', output) after `timeout` seconds,
    when its whole process group is killed (a compiler's own children too)."""
    proc = subprocess.Popen(cmd, cwd=cwd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, start_new_session=True)
    output = Output()
    reader = threading.Thread(target=lambda: [output.add(chunk) for chunk in
                                              iter(lambda: proc.stdout.read1(1 << 16), b'')])
    reader.start()
    try:
        code = proc.wait(timeout=max(timeout, 0))
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
        code = 'timeout'
    # A process that left the group may hold the pipe open: not waited for.
    reader.join(10)
    return code, output.text()


def tangle(root, chapters_dir, chapters, out, line_directives=False):
    """Tangles `chapters` (paths relative to chapters_dir's parent) into out."""
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    cmd = [sys.executable, os.path.join(root, 'tools', 'noweb', 'tangle.py'), '--out', out]
    if line_directives:
        cmd.append('--line-directives')
    code, output = run(cmd + chapters, cwd=os.path.dirname(chapters_dir))
    if code != 0:
        raise BuildError(output)


def tree_hash(directory, extra=''):
    """A hash of a tangled tree's files, every byte of them: the tree is
    tangled without #line directives, so a line that starts with `#line` is
    the student's, and the compiler obeys it (two programs must never share
    a key)."""
    h = hashlib.sha256(extra.encode())
    for top, dirs, files in os.walk(directory):
        dirs.sort()
        for name in sorted(files):
            path = os.path.join(top, name)
            h.update(os.path.relpath(path, directory).encode() + b'\0')
            with open(path, 'rb') as f:
                data = f.read()
            # The length first: no file's end can pass for the next name.
            h.update(b'%d\0' % len(data) + data)
    return h.hexdigest()[:32]


def files_hash(root, patterns):
    h = hashlib.sha256()
    for pattern in patterns:
        for path in sorted(glob.glob(os.path.join(root, pattern))):
            with open(path, 'rb') as f:
                data = f.read()
            h.update(os.path.relpath(path, root).encode() + b'\0%d\0' % len(data) + data)
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


def compile_all(jobs, commands, timeout=lambda: 900):
    """Runs (argv, cwd) compile commands, `jobs` at a time, each within
    timeout() seconds (what is left of a build's time when it starts);
    returns (status, output) of the first that failed, or None."""
    with concurrent.futures.ThreadPoolExecutor(max(1, jobs)) as pool:
        results = list(pool.map(lambda c: run(c[0], cwd=c[1], timeout=timeout()), commands))
    for code, output in results:
        if code != 0:
            return code, output
    return None


def reference_chapters(root, number):
    chapters = sorted(glob.glob(os.path.join(root, 'chapters', '[0-9][0-9]-*.md')))
    return [p for p in chapters if os.path.basename(p)[:2] <= number]


def install(built, binary):
    """Copies a binary just built to its place in the cache, whole or not at
    all: another grader may take it from there at any moment."""
    with open(built, 'rb') as source, replacing(binary, mode=0o755, binary=True) as f:
        shutil.copyfileobj(source, f)


# ---------------------------------------------------------------------------
# The judge

def judge_key(root, number):
    """The judge's cache key: a hash of every input of its build."""
    chapters = reference_chapters(root, number)
    tests = ['tests/ch%s/*' % number, 'tests/hidden/ch%s/*' % number, 'tests/calls/*']
    # A chapter's tests may include an earlier chapter's headers (chapter 7's
    # use chapter 6's scenes and checks).
    tests += ['tests/ch%s/*.h' % os.path.basename(p)[:2] for p in chapters
              if os.path.basename(p)[:2] < number]
    return hashlib.sha256((files_hash(root, [os.path.relpath(p, root) for p in chapters]) +
                           files_hash(root, tests + TANGLE_TOOLS) +
                           ' '.join(JUDGE_CXXFLAGS)).encode()).hexdigest()[:32]


def judge(cache, root, number, jobs=2):
    """The judge of chapter `number`, built from the book's code (cached)."""
    chapters = reference_chapters(root, number)
    entry = os.path.join(cache, 'judge-%s-%s' % (number, judge_key(root, number)))
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
                commands.append(([CXX] + JUDGE_CXXFLAGS + ['-DLRT_JUDGE', '-I', src, '-I',
                                  'tests', '-c', source, '-o', obj], root))
            failed = compile_all(jobs, commands)
            if failed is None:
                code, output = run([CXX, '-o', os.path.join(work, 'judge')] + objects +
                                   ['-lgtest', '-pthread'])
                failed = (code, output) if code != 0 else None
            if failed is not None:
                raise BuildError('the judge of chapter %s (the book\'s own code and tests) '
                                 'does not build:\n%s' % (number, failed[1][-4000:]))
            # The judge holds the hidden tests: for the grader's eyes only.
            os.makedirs(entry, mode=0o700, exist_ok=True)
            os.chmod(entry, 0o700)
            install(os.path.join(work, 'judge'), binary)
            return binary
        finally:
            shutil.rmtree(work, ignore_errors=True)


# ---------------------------------------------------------------------------
# Workers

def call_files(root, number):
    """The files of chapter `number`'s exercise calls that a worker's build
    copies: the framework, the chapter's calls, and the earlier chapters'
    calls, which they may include (chapter 7's build on chapter 6's scenes
    as values)."""
    earlier = [os.path.relpath(p, root) for p in sorted(glob.glob(
        os.path.join(root, 'tests', 'ch[0-9][0-9]', 'exercise_calls.h')))
        if os.path.basename(os.path.dirname(p))[2:] < number]
    return CALL_SOURCES + earlier + ['tests/ch%s/exercise_calls.h' % number]


class WorkerBuild:
    """Builds workers of chapter `number` from directories of chapters."""

    def __init__(self, cache, root, number, cxxflags=None, jobs=2, time_limit=900,
                 memory_mb=0):
        self.cache, self.root, self.number = cache, root, number
        # The limits of one worker's build (the grader's --compile-time-limit
        # and --memory-limit): seconds in all, MB per compiler process.
        self.time_limit, self.memory_mb = time_limit, memory_mb
        self.deadline = None     # when the build of the student's code must end
        self.cxxflags = cxxflags or WORKER_CXXFLAGS
        self.jobs = jobs
        self.ccache = sandbox.compile_cache(os.path.join(cache, 'ccache'))
        self.calls_header = 'ch%s/exercise_calls.h' % number
        self.call_files = call_files(root, number)
        self._needed = None      # the set needed() found, once it has

    def build(self, chapters_dir, chapters, label):
        """The worker for the chapters (file names in chapters_dir), or a
        BuildError whose output names the chapters' lines."""
        work = sandbox.compile_dir('worker-', self.cache)
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
                # Found first: the book's build is not timed against the student.
                self.needed()
                self.deadline = time.monotonic() + self.time_limit
                failure = self._compile(work)
                if failure is not None and self._limit_hit(*failure):
                    raise BuildError(self._limit_hit(*failure))
                if failure is not None:
                    # Again with #line directives, for errors at the chapters' lines.
                    tangle(self.root, chapters_dir, ['chapters/' + c for c in chapters],
                           src, line_directives=True)
                    again = self._compile(work)
                    raise BuildError((failure if again is None or self._limit_hit(*again)
                                      else again)[1])
                os.makedirs(entry, exist_ok=True)
                # Copied, not moved: work may be on another file system
                # (sandbox.compile_dir), and the entry must be the grader's.
                install(os.path.join(work, 'worker'), binary)
                return binary
        finally:
            self.deadline = None
            shutil.rmtree(work, ignore_errors=True)

    def _time_left(self):
        return 900 if self.deadline is None else self.deadline - time.monotonic()

    def _limit_hit(self, code, output):
        """What a failed step of the build says of the limit it went over
        (a compiler over a limit dies with words of its own), or None."""
        if code == 'timeout':
            return ('the compile took longer than %d s (the time limit of a build)'
                    % self.time_limit)
        if self.memory_mb and re.search(r'out of memory|memory exhausted|Cannot allocate '
                                        r'memory|std::bad_alloc', output):
            return ('the compile ran out of memory (a compiler process may use %d MB)'
                    % self.memory_mb)
        if re.search(r'File size limit exceeded|signal 25\b|File too large', output):
            return 'the compile wrote a file larger than %d MB' % BUILD_FILE_MB
        return None

    def _prepare(self, work):
        for rel in self.call_files:
            target = os.path.join(work, rel)
            os.makedirs(os.path.dirname(target), exist_ok=True)
            shutil.copy(os.path.join(self.root, rel), target)
        os.makedirs(os.path.join(work, 'obj'), exist_ok=True)
        sandbox.hand_over(work)

    def _command(self, work, argv):
        limits = sandbox.compile_limits(self.memory_mb, BUILD_FILE_MB)
        wrapped, cwd = sandbox.compile_command(argv, work, self.ccache)
        return (limits + wrapped, cwd)

    def _cxx(self):
        # Diagnostics without the source lines they point at: a student's
        # code can cause errors in the book's code of other exercises, whose
        # lines the grader must not show (tools/grading/grade.py, HIDDEN_DIAGNOSTIC).
        return (['ccache'] if self.ccache else []) + [CXX] + self.cxxflags + [
            '-fdiagnostics-plain-output', '-Isrc', '-Itests']

    def _compile(self, work, sources=None):
        """Compiles the worker in `work` (src/ tangled); None, or the
        (status, output) of the step that failed."""
        self._prepare(work)
        all_sources = library_sources(os.path.join(work, 'src'))
        needed = self.needed() if sources is None else sources
        todo = [s for s in all_sources if s in needed]
        commands = [self._command(work, self._cxx() + [
            '-DLRT_WORKER', '-DLRT_CALLS_HEADER="%s"' % self.calls_header,
            '-c', 'tests/calls/worker.cpp', '-o', 'obj/worker.o']),
            self._command(work, self._cxx() + ['-c', 'tests/calls/wall.cpp', '-o', 'obj/wall.o'])]
        for s in todo:
            commands.append(self._command(work, self._cxx() + [
                '-c', 'src/' + s, '-o', 'obj/' + s.replace('/', '_') + '.o']))
        failed = compile_all(self.jobs, commands, self._time_left)
        if failed is not None:
            return failed
        for attempt in (0, 1):
            objects = ['obj/worker.o'] + ['obj/' + s.replace('/', '_') + '.o' for s in todo]
            argv = [CXX, '-static', '-o', 'worker'] + objects + WALL_LINK + ['-pthread']
            code, output = run(*self._command(work, argv), timeout=self._time_left())
            if code == 0:
                return None
            rest = [s for s in all_sources if s not in todo]
            if attempt or not rest or 'undefined reference' not in output:
                return code, output
            # The student's code calls into more of the library than the
            # book's does: compile the rest too.
            failed = compile_all(self.jobs, [self._command(work, self._cxx() + [
                '-c', 'src/' + s, '-o', 'obj/' + s.replace('/', '_') + '.o']) for s in rest],
                self._time_left)
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
            files_hash(self.root, self.call_files + TANGLE_TOOLS) +
            ' '.join(self.cxxflags)).encode()
        ).hexdigest()[:32]
        record = os.path.join(self.cache, 'needed-%s-%s' % (self.number, key))
        with Locked(record):
            if os.path.isfile(record):
                with open(record) as f:
                    self._needed = set(f.read().split())
                return self._needed
            work = sandbox.compile_dir('needed-', self.cache)
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
                code, out = run([CXX, '-static', '-o', 'probe', 'obj/worker.o', 'lib.a'] +
                                WALL_LINK + ['-pthread', '-Wl,--trace'], cwd=work)
                taken = set(re.findall(r'lib\.a\((\S+?)\.o\)', out))
                self._needed = {s for s in sources if s.replace('/', '_') in taken}
                with open(record, 'w') as f:
                    f.write('\n'.join(sorted(self._needed)) + '\n')
            finally:
                shutil.rmtree(work, ignore_errors=True)
        return self._needed
