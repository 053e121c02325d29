"""The worker's wall (tests/calls/wall.cpp, docs/grading.md "The sandbox"):
a seccomp filter that the worker installs at its entry point, before the C
library and any of the student's code, and that holds the same in both
isolation modes.

- WallProbeTest: a small static program linked as the worker is (wall.cpp,
  its entry point) tries what the filter denies and what it allows, from a
  static initializer and from main; and where the kernel refuses the filter
  (a parent's filter that denies seccomp), the program does not run at all.
- WallGradingTest: chapter 5 graded by tools/grading/grade.py in a scratch copy of
  the repository, in both modes (bubblewrap; the fallback without
  namespaces, forced by a failing `bwrap` first on PATH), as one batch per
  mode of three submissions:
  - `solution`: the book's chapter: full marks.
  - `attacks`: ex-5.9's region, written as a student could (no asm, no
    attributes, no directives, no reserved names, its brackets balanced),
    runs its attacks in its first call (a region cannot leave its function,
    so no earlier; the probe covers static initializers): it reads the
    book's chapter (every solution) with stdio relative to the judge's
    working directory, with syscall(openat) by absolute path, and through
    popen("cat ..."); reads the hidden tests with syscall(open); copies
    the chapter out with std::system; writes a file with fopen; connects to
    a socket the test listens on; forks a child that renames itself, leaves
    the session and writes a file; and runs /bin/sh with execve (in a
    second child, or in place of the worker when there is none). Then it
    throws what each got.
  - `killer`: ex-5.9 calls kill(-1, SIGKILL).
  The feedback must hold no line of the book's solutions of ex-5.10 and
  ex-5.11 nor of the hidden tests; every attack must get EPERM; no file may
  be written outside the results, no connection made, no process left; and
  the other exercises must score what the book's code earns.

Without the filter (lrt_wall_install returning at once), in the fallback the
chapter's solutions show in the feedback, the files are written, the
connection is made, and kill(-1, SIGKILL) returns 0 (sent to every other
process of the sandbox's uid); with bubblewrap the attacks get other errors
than EPERM (or succeed inside the sandbox: fork, socket).
"""
import ctypes
import json
import os
import platform
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import test_grade as tg  # noqa: E402

WALL = os.path.join(tg.ROOT, 'tests', 'calls', 'wall.cpp')
X86_64 = platform.machine() == 'x86_64'
# The name the attacks' forked child takes, which the test looks for.
CHILD = 'lrtwallchild'
# Seconds per call: the first call of a worker runs every attack.
TIME_LIMIT = 5
EPERM = 1

# ---------------------------------------------------------------------------
# The probe

PROBE = r'''
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>
#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <sys/uio.h>
#include <unistd.h>

static std::string got;
static void note(const char *what, long result) {
    got += std::string(what) + "=" + std::to_string(result);
    if (result < 0) got += "/e" + std::to_string(errno);
    got += " ";
}
// Before main, as a student's inline variable would.
static int early = [] {
    note("init-openat", ::syscall(SYS_openat, AT_FDCWD, "/etc/hostname", O_RDONLY));
    return 0;
}();

int main(int argc, char **argv) {
    std::string what = argc > 1 ? argv[1] : "";
    if (what == "abort") std::abort();
    if (what == "x32") ::syscall(0x40000000 | SYS_getpid);
    if (what == "int80") {
        // Machine code for `mov $20, %eax; int $0x80; ret` (getpid of the
        // 32-bit ABI), run from memory made executable.
        static const unsigned char code[] = {0xb8, 20, 0, 0, 0, 0xcd, 0x80, 0xc3};
        void *page = mmap(nullptr, 4096, PROT_READ | PROT_WRITE,
                          MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        std::memcpy(page, code, sizeof(code));
        mprotect(page, 4096, PROT_READ | PROT_EXEC);
        reinterpret_cast<void (*)()>(page)();
    }
    {
        std::ifstream in("/etc/hostname");
        note("ifstream", in ? 0 : -1);
    }
    note("fopen", std::fopen("/etc/hostname", "r") ? 0 : -1);
    pid_t child = fork();
    if (child == 0) _exit(0);
    note("fork", child);
    note("socket", ::syscall(SYS_socket, AF_INET, SOCK_STREAM, 0));
    note("kill-all", kill(-1, 0));
    note("kill-group", kill(0, 0));
    note("kill-parent", kill(getppid(), 0));
    note("kill-self", kill(getpid(), 0));
    note("ptrace", ::syscall(SYS_ptrace, 2 /* PTRACE_PEEKDATA */, getppid(), 0, 0));
    char word[8];
    struct iovec local = {word, sizeof(word)}, remote = {nullptr, sizeof(word)};
    note("process_vm_readv", ::syscall(SYS_process_vm_readv, getppid(), &local, 1, &remote, 1, 0));
    note("shmget", ::syscall(SYS_shmget, 0, 4096, 01000 | 0600));
    note("write-5", write(5, "x", 1));
    note("dup", dup(1));
    note("prlimit", ::syscall(SYS_prlimit64, getppid(), RLIMIT_NOFILE, nullptr, nullptr));
    note("execve", execl("/bin/true", "true", (char *)nullptr));
    try {
        std::thread t([] {});
        t.join();
        note("thread", 0);
    } catch (const std::exception &) {
        note("thread", -1);
    }
    note("system", std::system("true"));
    char *block = new char[1 << 20];
    block[0] = 1;
    delete[] block;
    try {
        throw std::runtime_error("thrown");
    } catch (const std::exception &e) {
        note("caught", 0);
    }
    std::printf("%s\n", got.c_str());
    std::fflush(stdout);
    return 7;
}
'''

# A filter a parent installs (then execve), so that the probe's own is
# refused: seccomp(), and prctl(PR_SET_SECCOMP), fail with EPERM.
SECCOMP_DATA_NR, SECCOMP_DATA_ARG0 = 0, 16
BPF_LD_W_ABS, BPF_JEQ_K, BPF_RET_K = 0x20, 0x15, 0x06
SECCOMP_RET_ALLOW, SECCOMP_RET_ERRNO = 0x7fff0000, 0x00050000
NR_SECCOMP, NR_PRCTL, PR_SET_SECCOMP, PR_SET_NO_NEW_PRIVS = 317, 157, 22, 38
REFUSING = [
    (BPF_LD_W_ABS, 0, 0, SECCOMP_DATA_NR),
    (BPF_JEQ_K, 0, 1, NR_SECCOMP),
    (BPF_RET_K, 0, 0, SECCOMP_RET_ERRNO | EPERM),
    (BPF_JEQ_K, 0, 3, NR_PRCTL),
    (BPF_LD_W_ABS, 0, 0, SECCOMP_DATA_ARG0),
    (BPF_JEQ_K, 0, 1, PR_SET_SECCOMP),
    (BPF_RET_K, 0, 0, SECCOMP_RET_ERRNO | EPERM),
    (BPF_RET_K, 0, 0, SECCOMP_RET_ALLOW),
]


def refuse_filters():
    """In the child before execve: a filter under which no other can be
    installed."""
    code = b''.join(struct.pack('HBBI', *insn) for insn in REFUSING)
    program = ctypes.create_string_buffer(code)

    class Program(ctypes.Structure):
        _fields_ = [('len', ctypes.c_ushort), ('filter', ctypes.c_void_p)]
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl.argtypes = [ctypes.c_int, ctypes.c_ulong, ctypes.c_void_p,
                           ctypes.c_ulong, ctypes.c_ulong]
    prog = Program(len(REFUSING), ctypes.cast(program, ctypes.c_void_p))
    if (libc.prctl(PR_SET_NO_NEW_PRIVS, 1, None, 0, 0) != 0 or
            libc.prctl(PR_SET_SECCOMP, 2, ctypes.byref(prog), 0, 0) != 0):
        os._exit(99)


@unittest.skipUnless(X86_64, 'the filter is written for x86-64')
class WallProbeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix='lrt-wall-probe-')
        source = os.path.join(cls.tmp, 'probe.cpp')
        with open(source, 'w') as f:
            f.write(PROBE)
        cls.probe = os.path.join(cls.tmp, 'probe')
        # As tools/grading/build.py links a worker.
        subprocess.run(['g++', '-std=c++17', '-O0', '-c', WALL, '-o',
                        os.path.join(cls.tmp, 'wall.o')], check=True)
        subprocess.run(['g++', '-std=c++17', '-O0', '-static', '-o', cls.probe, source,
                        os.path.join(cls.tmp, 'wall.o'), '-Wl,-e,lrt_wall_entry',
                        '-pthread'], check=True)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def run_probe(self, *args, **options):
        return subprocess.run([self.probe] + list(args), capture_output=True, text=True,
                              timeout=20, **options)

    def test_only_what_answering_needs(self):
        proc = self.run_probe()
        self.assertEqual(proc.returncode, 7, proc.stderr)
        got = dict(item.split('=', 1) for item in proc.stdout.split())
        denied = '-1/e%d' % EPERM
        for what in ('init-openat', 'ifstream', 'fopen', 'fork', 'socket', 'kill-all',
                     'kill-group', 'kill-parent', 'ptrace', 'process_vm_readv', 'shmget',
                     'write-5', 'dup',
                     'prlimit', 'execve'):
            self.assertEqual(got.get(what), denied, (what, proc.stdout))
        # std::thread throws std::system_error; std::system cannot start a shell.
        self.assertTrue(got['thread'].startswith('-1'), got['thread'])
        self.assertNotEqual(got['system'], '0')
        self.assertEqual(got['kill-self'], '0')
        self.assertEqual(got['caught'], '0')

    def test_abort_still_ends_the_worker_with_its_signal(self):
        self.assertEqual(self.run_probe('abort').returncode, -6)

    def test_another_abi_kills(self):
        # x32 numbers and the 32-bit int 0x80 entry: SIGSYS, at once.
        self.assertEqual(self.run_probe('x32').returncode, -31)
        self.assertEqual(self.run_probe('int80').returncode, -31)

    def test_never_runs_without_the_filter(self):
        proc = self.run_probe(preexec_fn=refuse_filters)
        self.assertEqual(proc.returncode, 121, proc.stderr)
        self.assertIn('the kernel refused the system-call filter', proc.stderr)
        # Not even the static initializers ran.
        self.assertEqual(proc.stdout, '')


# ---------------------------------------------------------------------------
# Grading

def in_region(code):
    """ex-5.9's region (inside the loop of the first IntersectP) for code
    that defines `lrtWallReport` (a std::string); every call throws it. A
    region's brackets balance (tools/grading/compile_wall.py), so the code stays in
    the function: it runs at the first call, and no earlier (what a static
    initializer could do, the probe above checks)."""
    return '\n'.join([
        code,
        'throw std::runtime_error(lrtWallReport);',
        'Float invD = 0;',
        'int isNeg = 0;'])


# The attacks, as statements of a template's body. libc's syscall is
# declared after the book's header: a call that argument-dependent lookup
# finds at instantiation reaches it (an argument of a global type, ::div_t,
# through the `...`). Each attack notes what it got, "name=result" and errno
# on failure, and what it read.
ATTACKS = r"""
auto lrtSys = [](long n, long a = 0, long b = 0, long c = 0) -> long {
    auto call = [](auto global, long n, long a, long b, long c) -> long {
        return syscall(n, a, b, c, global);
    };
    return call(::div_t{}, n, a, b, c);
};
auto lrtNote = [](std::string &report, const char *name, long result) {
    report += std::string(" ") + name + "=" + std::to_string(result);
    if (result < 0) report += "/e" + std::to_string(errno);
};
// The solution lines of a chapter, which hold every exercise's answer.
auto lrtSolutions = [](const std::string &text) {
    std::string found;
    bool inside = false;
    for (size_t at = 0; at < text.size();) {
        size_t end = text.find('\n', at);
        if (end == std::string::npos) end = text.size();
        std::string line = text.substr(at, end - at);
        if (line == std::string("// END ") + "SOLUTION") inside = false;
        if (inside) found += line + " | ";
        if (line == std::string("// BEGIN ") + "SOLUTION") inside = true;
        at = end + 1;
    }
    return found;
};
auto lrtReadAll = [](std::FILE *f) {
    std::string text;
    char block[4096];
    for (size_t n; (n = std::fread(block, 1, sizeof(block), f)) > 0;) text.append(block, n);
    return text;
};
// A file's bytes through raw system calls: 0, or what a failed open returned.
auto lrtRawRead = [&](long number, const char *path, std::string &text) -> long {
    long fd = number == 257 ? lrtSys(257, -100L, (long)path, 0L) : lrtSys(2, (long)path, 0L);
    if (fd < 0) return fd;
    char block[4096];
    for (long n; (n = lrtSys(0, fd, (long)block, long(sizeof(block)))) > 0;)
        text.append(block, n);
    lrtSys(3, fd);
    return 0;
};
static const std::string lrtWallReport = [&] {
    const std::string when = "call";
    std::string report = "ATTACKS: [" + when + "]";
    std::string text;
    // The book's chapter, from the judge's working directory (the
    // repository), with stdio.
    if (std::FILE *f = std::fopen("chapters/05-slab-test.md", "r")) {
        report += " fopen-chapter=read: " + lrtSolutions(lrtReadAll(f));
        std::fclose(f);
    } else {
        lrtNote(report, "fopen-chapter", -1);
    }
    // The same by its absolute path, with openat.
    long r = lrtRawRead(257, {repo} "/chapters/05-slab-test.md", text);
    lrtNote(report, "openat-chapter", r);
    if (r == 0) report += " read: " + lrtSolutions(text);
    // The hidden tests, with open.
    text.clear();
    r = lrtRawRead(2, {repo} "/tests/hidden/ch05/test_ex5_hidden.cpp", text);
    lrtNote(report, "open-hidden", r);
    if (r == 0) report += " read: " + text.substr(0, 600);
    // Through a shell.
    if (std::FILE *p = ::popen("cat chapters/05-slab-test.md", "r")) {
        report += " popen=read: " + lrtSolutions(lrtReadAll(p));
        ::pclose(p);
    } else {
        lrtNote(report, "popen", -1);
    }
    report += " system=" + std::to_string(std::system(
        ("cp chapters/05-slab-test.md " {markers} "/system-copy-" + when).c_str()));
    // A file outside.
    std::FILE *out = std::fopen(({markers} "/fopen-" + when).c_str(), "w");
    lrtNote(report, "fopen-write", out ? 0 : -1);
    if (out) {
        std::fputs("written by the worker\n", out);
        std::fclose(out);
    }
    // The network: a socket the test listens on, 127.0.0.1:{port}.
    long s = lrtSys(41, 2L, 1L, 0L);
    lrtNote(report, "socket", s);
    if (s >= 0) {
        unsigned char address[16] = {2, 0, {port} >> 8, {port} & 255, 127, 0, 0, 1};
        long c = lrtSys(42, s, (long)address, 16L);
        lrtNote(report, "connect", c);
        if (c == 0) lrtSys(1, s, (long)"leaked", 6L);
        lrtSys(3, s);
    }
    // A child that outlives the worker and writes a file.
    long child = lrtSys(57);
    if (child == 0) {
        lrtSys(157, 15L, (long)"{child}");          // prctl(PR_SET_NAME)
        lrtSys(112);                                // setsid()
        long fd = lrtSys(2, (long)({markers} "/forked-" + when).c_str(), 01101L, 0644L);
        if (fd >= 0) lrtSys(3, fd);
        long ts[2] = {30, 0};
        lrtSys(35, (long)ts, 0L);                   // 30 s
        lrtSys(60, 0L);
    }
    lrtNote(report, "fork", child);
    // Another program: in a second child if there can be one, else in place
    // of the worker (execve returns only if it failed).
    long spawned = child > 0 ? lrtSys(57) : 0L;
    if (spawned == 0) {
        std::string command = "cp chapters/05-slab-test.md " {markers} "/exec-copy-" + when;
        const char *argv[] = {"sh", "-c", command.c_str(), nullptr};
        const char *envp[] = {"PATH=/usr/bin:/bin", nullptr};
        long e = lrtSys(59, (long)"/bin/sh", (long)argv, (long)envp);
        if (child > 0) lrtSys(60, 0L);
        lrtNote(report, "execve", e);
    } else {
        lrtNote(report, "spawned", spawned);
    }
    return report;
}();
"""

KILLER = r"""
auto lrtSys = [](long n, long a = 0, long b = 0) -> long {
    auto call = [](auto global, long n, long a, long b) -> long {
        return syscall(n, a, b, global);
    };
    return call(::div_t{}, n, a, b);
};
static const std::string lrtWallReport = [&] {
    long r = lrtSys(62, -1L, 9L);
    return "ATTACKS: kill(-1, SIGKILL)=" + std::to_string(r) + "/e" +
           std::to_string(r < 0 ? errno : 0);
}();
"""


# What each attack must have got with the filter, in both modes: EPERM.
DENIED = ['fopen-chapter', 'openat-chapter', 'open-hidden', 'popen', 'fopen-write',
          'socket', 'fork', 'execve']


def strings(value):
    """Every string in a JSON value, keys too."""
    if isinstance(value, str):
        return [value]
    if isinstance(value, dict):
        return [s for k, v in value.items() for s in [k] + strings(v)]
    if isinstance(value, list):
        return [s for v in value for s in strings(v)]
    return []


class Listener:
    """A TCP socket on 127.0.0.1 that records what connects to it."""
    def __init__(self):
        self.sock = socket.socket()
        self.sock.bind(('127.0.0.1', 0))
        self.sock.listen(16)
        self.sock.settimeout(0.2)
        self.port = self.sock.getsockname()[1]
        self.connections, self.done = [], False
        self.thread = threading.Thread(target=self.accept)
        self.thread.start()

    def accept(self):
        while not self.done:
            try:
                conn, peer = self.sock.accept()
            except OSError:
                continue
            self.connections.append(peer)
            conn.close()

    def close(self):
        self.done = True
        self.thread.join()
        self.sock.close()


@unittest.skipUnless(os.geteuid() == 0 and X86_64,
                     'root (the sandbox drops to its own user, the fallback needs root), '
                     'and the filter is written for x86-64')
class WallGradingTest(unittest.TestCase):
    maxDiff = None

    @classmethod
    def setUpClass(cls):
        owner, cls.points = tg.chapter5()
        cls.attacked = owner[tg.F9]
        chapter = tg.read(os.path.join(tg.ROOT, tg.CHAPTER))
        # The lines the feedback must never show: the book's solutions of the
        # exercises not attacked, and the hidden tests' lines (and the
        # identifiers only they use).
        cls.secret_lines = []
        for fragment in (tg.F10,) + tg.F11:
            first, last = tg.region(chapter, fragment)
            cls.secret_lines += [l.strip() for l in chapter.split('\n')[first:last + 1]]
        public = chapter + ''.join(tg.read(p) for p in tg.test_sources('05', False))
        cls.hidden_lines = [l.strip() for p in tg.test_sources('05', True)
                            for l in tg.read(p).split('\n')
                            if len(l.strip()) >= 24 and l.strip() not in public]
        cls.hidden_words = tg.hidden_only_identifiers(['05'])
        assert cls.secret_lines and cls.hidden_lines

        cls.tmp = tempfile.mkdtemp(prefix='lrt-grade-wall-')
        # Reachable by the sandbox's user, as a grader's repository and /tmp
        # are: without namespaces only the filter stands in the way.
        os.chmod(cls.tmp, 0o755)
        cls.copy = os.path.join(cls.tmp, 'repo')
        tg.copy_book(tg.ROOT, cls.copy)
        cls.markers = os.path.join(cls.tmp, 'markers')
        os.makedirs(cls.markers)
        os.chmod(cls.markers, 0o1777)
        cls.listener = Listener()
        cls.subs = os.path.join(cls.tmp, 'submissions')
        code = ATTACKS
        for name, value in (('repo', json.dumps(cls.copy)),
                            ('markers', json.dumps(cls.markers)),
                            ('port', str(cls.listener.port)), ('child', CHILD)):
            code = code.replace('{%s}' % name, value)
        tg.put_chapter(cls.subs, 'solution', chapter)
        tg.put_chapter(cls.subs, 'attacks', tg.replace_region(chapter, tg.F9, in_region(code)))
        tg.put_chapter(cls.subs, 'killer', tg.replace_region(chapter, tg.F9, in_region(KILLER)))
        cls.no_bwrap = tg.failing_bwrap(os.path.join(cls.tmp, 'no-bwrap'))
        cls.graded = {}

    @classmethod
    def tearDownClass(cls):
        cls.listener.close()
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def grade(self, mode):
        """The batch graded in the mode, once: {submission: (results.json,
        the feedback's text)}, and {'outside': what the grading changed
        outside its results: files of the copy and the submissions, files in
        the markers' folder, connections, processes left}."""
        if mode in self.graded:
            return self.graded[mode]
        for name in os.listdir(self.markers):
            os.remove(os.path.join(self.markers, name))
        del self.listener.connections[:]
        fallback = mode != 'bubblewrap'
        out = os.path.join(self.tmp, 'out-' + mode.split()[0])
        env = dict(os.environ, PYTHONDONTWRITEBYTECODE='1')
        if fallback:
            env['PATH'] = self.no_bwrap + os.pathsep + env['PATH']
        watched = tg.tree_files(self.copy, skipped=()) + tg.tree_files(self.subs, skipped=())
        before = tg.snapshot(watched)
        start = time.monotonic()
        proc = subprocess.run(
            [sys.executable, os.path.join(self.copy, 'tools', 'grading', 'grade.py'),
             '--cache', os.path.join(self.tmp, 'cache'), '--batch', self.subs, '--out', out,
             '--chapters', '05', '--time-limit', str(TIME_LIMIT)],
            cwd=self.copy, env=env, capture_output=True, text=True, timeout=1200)
        print('%s: graded in %.0f s' % (mode, time.monotonic() - start), file=sys.stderr)
        self.assertEqual(proc.returncode, 0, proc.stdout + proc.stderr)
        # Long enough for the forked child to have written its file, had it
        # lived.
        time.sleep(2)
        graded = {}
        for name in ('solution', 'attacks', 'killer'):
            with open(os.path.join(out, name, 'results.json'), encoding='utf-8') as f:
                results = json.load(f)
            self.assertIn(mode, results['output'])
            text = '\n'.join(strings(results) + [tg.read(os.path.join(out, name, f))
                                                 for f in ('results.txt', 'junit.xml')])
            graded[name] = (results, text)
        graded['outside'] = {
            'changed': tg.changed(before, tg.snapshot(
                tg.tree_files(self.copy, skipped=()) + tg.tree_files(self.subs, skipped=()))),
            'markers': sorted(os.listdir(self.markers)),
            'connections': list(self.listener.connections),
            'processes': tg.processes_named(CHILD)}
        self.graded[mode] = graded
        return graded

    def check_no_secret(self, text):
        for line in self.secret_lines + self.hidden_lines:
            self.assertFalse(line in text, 'the feedback shows %r' % line)
        for word in self.hidden_words:
            self.assertFalse(word in text, 'the feedback shows %r' % word)

    def check_others(self, results):
        """The exercises not attacked pass every test."""
        for test in results['tests']:
            if test['name'].split()[0] != self.attacked:
                self.assertEqual(test['status'], 'passed', (test['name'], test['output']))

    def check_solution(self, mode):
        results, text = self.grade(mode)['solution']
        for test in results['tests']:
            self.assertEqual(test['status'], 'passed', (test['name'], test['output']))
        self.assertAlmostEqual(results['score'], sum(self.points.values()), places=3)

    def check_attacks(self, mode):
        graded = self.grade(mode)
        results, text = graded['attacks']
        attacked = [t for t in results['tests'] if t['name'].split()[0] == self.attacked]
        self.assertTrue(attacked)
        with self.subTest('the feedback holds no solution or hidden test'):
            self.check_no_secret(text)
        with self.subTest('every attack got EPERM'):
            for test in attacked:
                # Thrown: the worker lived through every attack, and says
                # what each got.
                self.assertIn('**FAIL**', test['output'], test['name'])
                # A hidden test shows nothing the code threw.
                if test['visibility'] != 'visible':
                    continue
                self.assertIn('ATTACKS:', test['output'], test['name'])
                for when in ('call',):
                    report = test['output'].split('[%s]' % when, 1)[1].split('[', 1)[0]
                    for name in DENIED:
                        self.assertIn(' %s=-1/e%d' % (name, EPERM), report,
                                      (when, name, report))
        with self.subTest('nothing outside: no file, connection or process'):
            self.assertEqual(graded['outside'], {'changed': [], 'markers': [],
                                                 'connections': [], 'processes': []})
        with self.subTest('the other exercises score the book\'s points'):
            self.check_others(results)
            others = sum(p for e, p in self.points.items() if e != self.attacked)
            self.assertAlmostEqual(results['score'], others, places=3)

    def check_killer(self, mode):
        results, text = self.grade(mode)['killer']
        attacked = [t for t in results['tests'] if t['name'].split()[0] == self.attacked]
        self.assertTrue(attacked)
        with self.subTest('kill(-1, SIGKILL) got EPERM, and the worker lived'):
            for test in attacked:
                self.assertIn('**FAIL**', test['output'], test['name'])
                if test['visibility'] == 'visible':
                    self.assertIn('kill(-1, SIGKILL)=-1/e%d' % EPERM, test['output'],
                                  test['name'])
        with self.subTest('the other exercises score the book\'s points'):
            self.check_others(results)
            others = sum(p for e, p in self.points.items() if e != self.attacked)
            self.assertAlmostEqual(results['score'], others, places=3)

    def test_book_solution_full_marks_bubblewrap(self):
        self.check_solution('bubblewrap')

    def test_book_solution_full_marks_without_namespaces(self):
        self.check_solution('unprivileged user')

    def test_attacks_fail_bubblewrap(self):
        self.check_attacks('bubblewrap')

    def test_attacks_fail_without_namespaces(self):
        self.check_attacks('unprivileged user')

    def test_kill_of_every_process_fails_bubblewrap(self):
        self.check_killer('bubblewrap')

    def test_kill_of_every_process_fails_without_namespaces(self):
        self.check_killer('unprivileged user')


if __name__ == '__main__':
    unittest.main()
