"""Command lines that run a student's code, or compile it, in isolation.

The grader (tools/grading/grade.py, docs/grading.md) never runs a student's code
itself. What runs the code, the worker, is started through the command line
that worker_command() builds; what compiles it, through compile_command().

Isolation, the best this machine allows (isolation() says which):

- "bubblewrap": the program runs in bwrap with new user, PID, network, IPC,
  UTS and cgroup namespaces, in its own session, killed with its parent, on an
  empty root that holds only what it needs (the worker: its static binary; the
  compiler: /usr and the build directory), a private /tmp, no environment
  but PATH and HOME, no capabilities and no way to make more user namespaces.
  If the grader is root, the sandbox also runs as an unprivileged user of its
  own, so that the process limit counts only its processes.
- "unprivileged user": root without a working bwrap (some containers forbid
  namespaces): the worker runs as that unprivileged user with the same
  limits; it can read what the world can read, so the grader makes its own
  files unreadable to others (protect()).
- "none": neither: only the limits. The grader refuses this unless told
  otherwise (--allow-no-sandbox), since the code then runs as the grader.

In every mode the worker also installs a system-call filter on itself at its
entry point, before any of the student's code runs (tests/calls/wall.cpp):
it opens no file, starts no process or thread, connects nowhere and signals
only itself. Without namespaces, that filter is what keeps the worker from
the files the world can read.

Limits (prlimit): address space, CPU seconds, file size, processes, open
files, no core dumps.
"""
import ctypes
import fcntl
import functools
import os
import resource
import shutil
import signal
import stat
import subprocess
import tempfile
import time

# The unprivileged user the sandbox runs as when the grader is root: a uid
# that no account uses, so that RLIMIT_NPROC counts the sandbox alone.
SANDBOX_UID = 64123
# The group of every sandbox user: the one thing they share is the compiler
# cache of the sandboxed compiles (compile_cache()).
SANDBOX_GID = SANDBOX_UID

BWRAP_COMMON = ['--unshare-all', '--unshare-user', '--die-with-parent', '--new-session',
                '--disable-userns', '--cap-drop', 'ALL', '--hostname', 'sandbox',
                '--proc', '/proc', '--dev-bind', '/dev/null', '/dev/null',
                '--clearenv', '--setenv', 'PATH', '/usr/bin:/bin',
                '--setenv', 'HOME', '/tmp']


# bwrap's own first process in the new PID namespace outlives the bwrap that
# the grader waits for by a moment, and so is left to the nearest subreaper or
# to the machine's first process, which in a container may never reap it.
# The compiler and the probe need no such process: the command itself is the
# namespace's first process (it still ends with the sandbox). The worker keeps
# it: a namespace's first process ignores the signals it sends itself, so a
# student's abort() would end differently; the judge reaps what its workers
# leave (tests/calls/judge.cpp).
NO_INIT = ['--as-pid-1']


def _is_root():
    return os.geteuid() == 0


# The processes of one uid share one RLIMIT_NPROC count, in a sandbox or not:
# two graders running at once (make grade-batch runs two) whose workers had
# one uid would share it, and a fork bomb in one student's worker would stop
# the other student's worker from starting. Each grader process therefore
# takes a uid of its own from this range, held by a lock while it runs.
SANDBOX_UIDS = range(SANDBOX_UID, SANDBOX_UID + 256)


# Where the uid locks are: one directory for every grader of the machine, so
# /run (root's: only a root grader takes uids), never the temporary
# directory, which TMPDIR or a private /tmp (a grader in a container of its
# own, such as the autograder's test) makes another. Two graders that saw
# different directories took the same uid: they shared its process limit,
# and each, taking the uid, killed the other's workers (end_processes_of).
UID_LOCKS = '/run/lrt-sandbox-uids'


def _uid_lock_dir():
    """A directory only this user can enter, for the uid locks (a worker in
    the fallback without namespaces must not hold them)."""
    path = UID_LOCKS
    try:
        os.mkdir(path, 0o700)
    except FileExistsError:
        pass
    info = os.lstat(path)
    if (not stat.S_ISDIR(info.st_mode) or info.st_uid != os.geteuid()
            or info.st_mode & 0o077):
        raise RuntimeError('%s is not a directory of this user alone' % path)
    return path


@functools.lru_cache(maxsize=None)
def sandbox_uid():
    """The uid of this grader's workers: the first of SANDBOX_UIDS that no
    other running grader holds."""
    directory = _uid_lock_dir()
    for uid in SANDBOX_UIDS:
        fd = os.open(os.path.join(directory, '%d.lock' % uid), os.O_RDWR | os.O_CREAT, 0o600)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(fd)
            continue
        end_processes_of(uid)
        return uid      # fd stays open, and the lock held, until this process ends
    raise RuntimeError('no free sandbox uid: %d graders are running' % len(SANDBOX_UIDS))


def end_processes_of(uid):
    """Kills every process of uid. The judge ends what each worker leaves
    (tests/calls/judge.cpp), but a grader that was killed outright ended
    nothing: a process its student left, a setsid() daemon in the fallback,
    would still run as the uid that the next grader takes, and could kill
    that grader's workers. kill(-1, ...) from a process of that uid reaches
    every process of the uid but itself: a child that has become the uid,
    and kills only once it is sure it has (as root, kill(-1) would reach
    every process of the machine)."""
    child = os.fork()
    if child == 0:
        ended = 1
        try:
            os.setgroups([])
            os.setgid(uid)
            os.setuid(uid)
            if os.getuid() == uid and os.geteuid() == uid:
                try:
                    os.kill(-1, signal.SIGKILL)
                except ProcessLookupError:
                    pass        # no process of the uid
                ended = 0
        finally:
            os._exit(ended)
    _, status = os.waitpid(child, 0)
    if status != 0:
        raise RuntimeError('could not end the processes of uid %d' % uid)


PR_SET_PDEATHSIG = 1
PR_SET_CHILD_SUBREAPER = 36


def adopt_orphans():
    """Makes this grader the parent of every process that its judges leave
    when they die: a worker whose judge was killed at the exercise's
    deadline, a sandbox whose parent died. Without this they would go to the
    container's first process, which may be no init and reap nothing; each
    would stay a zombie of the sandbox's user and count against its process
    limit. reap_orphans() then ends and reaps them."""
    libc = ctypes.CDLL(None, use_errno=True)
    if libc.prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0) != 0:
        raise OSError(ctypes.get_errno(), 'prctl(PR_SET_CHILD_SUBREAPER)')


def judge_process(memory_mb):
    """Popen's preexec_fn for a judge: it dies with its grader
    (die_with_parent) and may not take more than `memory_mb` of address
    space. The judge runs no student code, but it keeps what the workers
    answer and every failure it finds in it: a reply shaped to make the tests
    fail a million times would otherwise grow it until the machine, and the
    other submissions graded on it, ran out of memory. Its workers set their
    own, smaller limit."""
    def limit():
        die_with_parent()
        if memory_mb:
            size = memory_mb << 20
            resource.setrlimit(resource.RLIMIT_AS, (size, size))
    return limit


def die_with_parent():
    """In a child before it runs its program (Popen's preexec_fn): it is
    killed when the grader dies. A grader killed outright (a batch's time
    limit for one submission, an outer timeout) can end nothing: without
    this its judge would run on, starting the student's code in workers
    under a uid that the next grader takes. (The workers die with their
    judge the same way: setpriv --pdeathsig, or bubblewrap's
    --die-with-parent.)"""
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)


def reap_orphans(seconds=10):
    """Waits for the children this grader adopted, once they were killed;
    called when no process that the grader started itself is running."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        try:
            pid, _ = os.waitpid(-1, os.WNOHANG)
        except ChildProcessError:
            return          # no child left
        if pid == 0:
            time.sleep(0.01)


def _drop_privileges():
    """setpriv's arguments that make a root grader's sandbox unprivileged."""
    if not _is_root():
        return []
    uid = sandbox_uid()
    return ['setpriv', '--reuid=%d' % uid, '--regid=%d' % SANDBOX_GID,
            '--clear-groups', '--no-new-privs', '--pdeathsig=KILL', '--']


def _limits(memory_mb, cpu_seconds, processes, file_mb):
    args = ['prlimit', '--core=0', '--nofile=64', '--nproc=%d' % processes,
            '--fsize=%d' % (file_mb << 20), '--cpu=%d:%d' % (cpu_seconds, cpu_seconds + 1)]
    if memory_mb:
        args.append('--as=%d' % (memory_mb << 20))
    return args + ['--']


@functools.lru_cache(maxsize=None)
def isolation():
    """The isolation this machine gives: "bubblewrap", "unprivileged user" or
    "none". bwrap is tried for real, with the options the worker uses."""
    if shutil.which('bwrap'):
        probe = _drop_privileges() + ['bwrap'] + BWRAP_COMMON + NO_INIT + [
            '--tmpfs', '/tmp', '--ro-bind', '/usr', '/usr',
            '--symlink', 'usr/bin', '/bin', '--symlink', 'usr/lib', '/lib',
            '--symlink', 'usr/lib64', '/lib64', 'true']
        try:
            ok = subprocess.run(probe, stdin=subprocess.DEVNULL,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                timeout=30).returncode == 0
        except (OSError, subprocess.TimeoutExpired):
            ok = False
        if ok:
            return 'bubblewrap'
    if _is_root() and shutil.which('setpriv'):
        return 'unprivileged user'
    return 'none'


def describe():
    """One sentence for the feedback: how the student's code was isolated."""
    return {
        'bubblewrap': 'in a bubblewrap sandbox (no network, no view of the grader or '
                      'of other files, its own processes only), under a system-call '
                      'filter',
        'unprivileged user': 'as an unprivileged user, without namespaces (bubblewrap '
                             'cannot run here), under a system-call filter (no files, '
                             'no network, no other processes), with limits on memory, '
                             'time and processes',
        'none': 'WITHOUT ISOLATION (no bubblewrap and not root): only a system-call '
                'filter and limits on memory, time and processes',
    }[isolation()]


def worker_command(binary, memory_mb=1024, cpu_seconds=120, processes=16, file_mb=16):
    """The command line of a worker: the static binary `binary` (in a directory
    of its own that others may read), alone in the sandbox."""
    limits = _limits(memory_mb, cpu_seconds, processes, file_mb)
    kind = isolation()
    if kind == 'bubblewrap':
        return limits + _drop_privileges() + ['bwrap'] + BWRAP_COMMON + [
            '--size', str(64 << 20), '--tmpfs', '/tmp', '--chdir', '/tmp',
            '--ro-bind', binary, '/worker', '/worker']
    if kind == 'unprivileged user':
        return limits + _drop_privileges() + [binary]
    return limits + [binary]


def compile_limits(memory_mb, file_mb):
    """prlimit's arguments for a compile of a student's code: the compiler
    may be made to use memory and write files without end (templates, a
    huge constant array); its time the caller limits."""
    args = ['prlimit', '--core=0', '--fsize=%d' % (file_mb << 20)]
    if memory_mb:
        args.append('--as=%d' % (memory_mb << 20))
    return args + ['--']


# Where a root grader's compiles of students' code work, and the compiler
# cache they share: a directory that the sandbox's users may pass through
# (bwrap, running as one, must reach what it binds), whatever the grader's
# cache and temporary directory allow. Its entries are the users' own.
SANDBOX_DIR = '/var/tmp/lrt-sandbox'


def _sandbox_dir():
    os.makedirs(SANDBOX_DIR, exist_ok=True)
    info = os.lstat(SANDBOX_DIR)
    if not stat.S_ISDIR(info.st_mode) or info.st_uid != 0:
        raise RuntimeError('%s is not a directory of root\'s' % SANDBOX_DIR)
    os.chmod(SANDBOX_DIR, 0o711)
    return SANDBOX_DIR


def compile_command(argv, build_dir, cache_dir=None):
    """(command line, working directory) that run the compiler `argv` on the
    files of `build_dir` (made by compile_dir()). A compile of a student's
    code never runs as root: a root grader runs it as the sandbox's
    unprivileged user, in either mode. With bubblewrap, the compiler also
    sees only /usr, build_dir (read-write, as /build, its working directory)
    and the compiler cache: a student's #include of a grader's file would
    find nothing. Without namespaces it runs in build_dir as that user. In
    both, what a student's code may hold keeps the compiler from naming any
    file (tools/grading/compile_wall.py)."""
    if isolation() != 'bubblewrap':
        return _drop_privileges() + argv, build_dir
    args = _drop_privileges() + ['bwrap'] + BWRAP_COMMON + NO_INIT + [
        '--ro-bind', '/usr', '/usr', '--symlink', 'usr/bin', '/bin',
        '--symlink', 'usr/lib', '/lib', '--symlink', 'usr/lib64', '/lib64',
        '--tmpfs', '/tmp', '--bind', build_dir, '/build', '--chdir', '/build']
    if cache_dir:
        args += ['--bind', cache_dir, '/ccache', '--setenv', 'CCACHE_DIR', '/ccache',
                 '--setenv', 'CCACHE_NOHASHDIR', '1', '--setenv', 'CCACHE_UMASK', '007']
    return args + argv, None


def compile_cache(path):
    """The compiler cache that compiles of students' code share, or None.
    With bubblewrap: for a root grader, one in SANDBOX_DIR that every sandbox
    user may write through the sandbox's group and that nothing but the
    sandboxed compiler sees; for another grader, path. Not without
    namespaces: there the sandbox's user would reach it outside any sandbox,
    and could rewrite what other compiles take from it; its compiles go
    without (a worker of the book's chapters compiles in seconds)."""
    if isolation() != 'bubblewrap' or not shutil.which('ccache'):
        return None
    if not _is_root():
        os.makedirs(path, exist_ok=True)
        return path
    path = os.path.join(_sandbox_dir(), 'ccache')
    os.makedirs(path, exist_ok=True)
    info = os.stat(path)
    if info.st_gid != SANDBOX_GID or info.st_mode & 0o7777 != 0o2770:
        os.chown(path, 0, SANDBOX_GID)
        os.chmod(path, 0o2770)
    return path


def compile_dir(prefix, parent):
    """A new directory for a compile of a student's code: in parent (the
    grader's cache), or, for a root grader, whose compiles run as the
    sandbox's user, in SANDBOX_DIR, since the cache holds what that user
    must not read (judges, verdicts); hand_over() then makes it that
    user's."""
    if _is_root() and isolation() != 'none':
        return tempfile.mkdtemp(prefix=prefix, dir=_sandbox_dir())
    return tempfile.mkdtemp(prefix=prefix, dir=parent)


def hand_over(path):
    """Makes the tree at path the sandbox user's, where compiles run as it."""
    if not _is_root() or isolation() == 'none':
        return
    uid = sandbox_uid()
    for top, dirs, files in os.walk(path):
        for name in dirs + files:
            os.lchown(os.path.join(top, name), uid, SANDBOX_GID)
    os.lchown(path, uid, SANDBOX_GID)


def protect(paths):
    """Without namespaces the worker sees the file system as its user does:
    make the grader's files unreadable to others."""
    for path in paths:
        if not os.path.exists(path):
            continue
        for top, dirs, files in os.walk(path):
            for name in dirs + files:
                full = os.path.join(top, name)
                if not os.path.islink(full):
                    os.chmod(full, os.stat(full).st_mode & ~0o007)
        os.chmod(path, os.stat(path).st_mode & ~0o007)
