"""What a compile of a student's code sees and shows (tools/grading/compile_wall.py,
docs/grading.md): no submission gets the book's solution of another exercise,
or of a later assignment, through the compiler.

A worker of ex-5.9 is compiled from the book's code with the student's text
in ex-5.9's regions, beside the book's solutions of ex-5.10 and ex-5.11 (in
the same header) and of chapters 2 to 4. The attacks ask the compiler to read
those files (`asm(".incbin")` with a path relative to the compile's working
directory, the same in both modes), to take the book's text that follows
into a raw string, to splice in another fragment (a noweb use), or to make
errors happen in the book's code so that the diagnostics quote it. Each is
graded in both isolation modes; no line of the book's other solutions may
appear in anything the grading writes or prints.

The lexer itself is checked on its own below, construct by construct, and
on the whole book (whose own code it must accept).
"""
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import test_grade as tg  # noqa: E402

sys.path.insert(0, tg.ROOT)
from tools.exercises import markup  # noqa: E402
from tools.grading import compile_wall, sandbox  # noqa: E402


def read_json(path):
    with open(path, encoding='utf-8') as f:
        return json.load(f)


def items(code):
    """(kind, text) of what scan() finds in code, and whether it ends open."""
    found = compile_wall.scan(code.split('\n'))
    return [(k, t) for _, k, t in found.items], found.open is not None


class ScanTest(unittest.TestCase):
    def assertRefused(self, code, kind=None):
        found, left_open = items(code)
        self.assertTrue(found or left_open, code)
        if kind:
            self.assertIn(kind, [k for k, _ in found], code)

    def assertAccepted(self, code):
        self.assertEqual(items(code), ([], False), code)

    def test_what_names_a_file_or_reaches_the_assembler(self):
        for code in ('#include "/etc/passwd"', '  #  define X 1', '/* */ #if 1',
                     '%:include <x>', 'int a; # include <x>'):
            self.assertRefused(code)
        self.assertRefused('#include "x"', 'directive')
        for word in ('asm', '__asm', '__asm__', '_Pragma', '__attribute__', '__attribute',
                     '__declspec'):
            self.assertRefused('%s("x");' % word, 'keyword')
        for code in ('[[gnu::section("x")]] int q;', 'int q [ /* */ [gnu::used]];',
                     '<:<:gnu::used:>:> int q;'):
            self.assertRefused(code)

    def test_what_reaches_the_assembler_through_a_macro(self):
        # glibc's __REDIRECT makes an asm label of its third argument,
        # __STRING stringizes, __glibc_macro_warning1 makes a _Pragma.
        for code in ('extern int __REDIRECT(f, (void), x;.incbin "y");',
                     'auto s = __STRING(x);', '__glibc_macro_warning1(GCC error "x")',
                     'int _Reserved = 0;'):
            self.assertRefused(code, 'reserved name')
        for digraph in ('<%', '%>', ':>'):
            self.assertRefused('int x %s' % digraph, 'digraph')

    def test_brackets_balance(self):
        for code in ('assert((', '))); {', '} } extern int f();', 'f(a[0)];'):
            self.assertIsNotNone(compile_wall.scan([code]).unbalanced, code)
        for code in ('f((a), [&] { return b[0]; });', '{ int x = (1); }',
                     'const char *s = "((("; // )'):
            self.assertIsNone(compile_wall.scan([code]).unbalanced, code)

    def test_what_changes_how_the_book_is_read(self):
        self.assertRefused('int a = 1; \\', 'line splice')
        self.assertRefused('int a = 1; \\  ', 'line splice')
        self.assertRefused('const char *s = "??=";', 'trigraph')
        self.assertRefused('int x = a<:0:>;', 'digraph')
        self.assertRefused('const char *s = R"x(')
        self.assertRefused('const char *s = u8R"(abc')
        self.assertRefused('/* open')
        self.assertRefused('const char *s = "open;')
        self.assertRefused("char c = 'x;")
        self.assertRefused('auto s = "<<Other fragment>>";', 'fragment use inside a literal')
        self.assertRefused('auto s = R"(\n<<Other fragment>>\n)";',
                           'fragment use inside a raw string')
        self.assertRefused('/* <<Other fragment>> */', 'fragment use inside a comment')

    def test_plain_cpp_is_accepted(self):
        for code in ('const char *s = "# include <x> asm __attribute__ ??";',
                     "char c = '#'; char d = '\\''; int n = 1'000'000;",
                     'double x = 1e+5, y = 0x1p-3, z = .5e-2;',
                     'auto s = R"lrt(a "quoted" ) #include)lrt";',
                     'auto t = u8"x", u = L"y"; char16_t c = u\'z\';',
                     '// asm("x") #include [[',
                     '/* multi-line\n   comment with # and asm */ int a;',
                     'std::vector<::lrt::Float> v; auto f = [&](int i) { return v[i]; };',
                     'int m[2][2] = {{1, 2}, {3, 4}}; (void)m[0][v[1]];',
                     'x <<= 2; y = a << b;', 'z = c >> 1;',
                     # a use compiles the book's code in one more place
                     '<<Other fragment>>'):
            self.assertAccepted(code)

    def test_the_book_passes_its_own_check(self):
        paths = sorted(glob.glob(os.path.join(tg.ROOT, 'chapters', '[0-9][0-9]-*.md')))
        book = markup.Book(paths, tests=False)
        for chapter in book.chapters:
            for exercise in chapter.exercises + [None]:
                mine = set(exercise.fragments) if exercise else set()
                self.assertEqual(compile_wall.check(chapter, chapter, str, mine), [],
                                 chapter.path)
            # and no solution region of the book holds any of it: a student
            # who writes what the book writes is never refused.
            for region in chapter.regions:
                scanned = compile_wall.scan([t for _, t in region.solution])
                self.assertEqual((scanned.items, scanned.open, scanned.spans),
                                 ([], None, []), (chapter.path, region.line(region.begin)))


# The ex-5.9 region's attacks. The paths are relative to the compile's
# working directory, which holds the tangled code in src/ in both modes.
def incbin_leak(files):
    """Code that puts each file's bytes into the worker and throws them."""
    lines = ['std::string lrtLeak;']
    for k, path in enumerate(files):
        label = 'lrtLeak%d' % k
        lines += ['asm(".ifndef %s\\n.pushsection .rodata\\n%s:\\n.incbin \\"%s\\"\\n'
                  '.byte 0\\n.popsection\\n.endif");' % (label, label, path),
                  '{ const char *p; asm("lea %s(%%%%rip), %%0" : "=r"(p)); lrtLeak += p; }'
                  % label]
    # A failure shows a few KB: the part around ex-5.11's solution.
    lines.append('throw std::runtime_error(lrtLeak.substr(lrtLeak.find("gamma(3)") - 300, '
                 '1000));')
    return '\n'.join(lines)


# glibc's __REDIRECT gives a declaration an asm label of its own text, which
# the compiler copies into the assembly, where `;` starts a new statement:
# an .incbin. GCC drops the label of a declaration inside a template
# function, so the region first closes the book's loop and function (and
# opens a dummy template that takes the book's rest). Found by a red team.
REDIRECT = r"""lrtLeak(b);
}
}
extern int __REDIRECT(lrtReadFn, (void), abort;.pushsection .rodata;.globl lrtFileData;lrtFileData:;.incbin "src/lrt/core/geometry.h";.byte 0;.popsection;call abort);
extern const char __REDIRECT(lrtFile, [1], lrtFileData);
inline void lrtLeak(const Bounds3<float> &box) {
    if (box.pMin.x == 12345.f) lrtReadFn();
    std::string lrtText(lrtFile);
    throw std::runtime_error(lrtText.substr(lrtText.find("Compute the union"), 3000));
}
template <typename T>
bool lrtRest(const Bounds3<T> &b, const Ray &ray, Float *hitt0, Float *hitt1) {
    Float t0 = 0, t1 = 0;
    for (int i = 0; i < 3; ++i) {
        Float invD = 0;
        int isNeg = 0;"""


def in_region(fragment, code):
    return lambda text: tg.inject(text, fragment, code)


# Each attack: (the fragment whose exercise it is graded as, the chapter).
ATTACKS = {
    # The book's headers as the compiler sees them: ex-5.10 and ex-5.11 in
    # slabtest.h, a later assignment's ex-2.12 to ex-2.14 in geometry.h.
    'incbin': (tg.F9, in_region(tg.F9, incbin_leak(['src/lrt/core/slabtest.h',
                                                    'src/lrt/core/geometry.h']))),
    'redirect': (tg.F9, in_region(tg.F9, REDIRECT)),
    # The book's text after the region, up to the first `)"`, in a string.
    'raw_string': (tg.F9, in_region(tg.F9, 'static const char *lrtText = R"(')),
    # The next exercise's fragment spliced in by the tangle, as a string.
    'fragment_use': (tg.F9, in_region(tg.F9, 'throw std::runtime_error(R"lrt(\n<<Widen tFar '
                                              'to cover rounding error>>\n)lrt");')),
    # A name that the book's ex-5.11 code then uses (gamma(3)): the error is
    # at ex-5.11's line, and its diagnostic would quote it.
    'diagnostic': (tg.F9, in_region(tg.F9, 'int gamma = 0; (void)gamma;')),
    # ex-5.11's two regions: the first opens a macro call that the second
    # closes, stringizing the book's ex-5.9 and ex-5.10 code between them
    # (a red team's).
    'across_regions': (tg.F11[0], lambda text: tg.replace_region(tg.replace_region(
        text, tg.F11[1], 'throw std::runtime_error(__STRING(('), tg.F11[0],
        ')));\n{ Float tNear = 0, tFar = 0;')),
}


class ChapterCheckTest(unittest.TestCase):
    """check() on chapter 5 with a student's text in it, as the grader
    composes it for ex-5.9."""
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix='lrt-compile-wall-check-')
        cls.text = tg.read(os.path.join(tg.ROOT, tg.CHAPTER))
        cls.book = cls.parse(cls.text)
        cls.mine = {tg.F9}

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    @classmethod
    def parse(cls, text):
        path = os.path.join(cls.tmp, os.path.basename(tg.CHAPTER))
        with open(path, 'w', encoding='utf-8') as f:
            f.write(text)
        return markup.Book([path], tests=False).chapters[0]

    def problems(self, text):
        return compile_wall.check(self.book, self.parse(text), str, self.mine)

    def test_the_students_region_may_hold_plain_code(self):
        self.assertEqual(self.problems(tg.inject(self.text, tg.F9, 'int lrtMine = (1);')), [])

    def test_a_region_balances_its_brackets(self):
        found = self.problems(tg.inject(self.text, tg.F9, 'assert(('))
        self.assertTrue(any('do not balance' in p for p in found), found)

    def test_no_change_around_another_exercises_solution(self):
        # <<Clip the parametric interval to slab i>> uses ex-5.11's <<Widen
        # tFar...>>: with --allow-changes-outside-exercises its own lines
        # must stay the book's, lest they wrap ex-5.11's code.
        clip = 'Float tNear = (b[isNeg][i] - ray.o[i]) * invD;'
        self.assertIn(clip, self.text)
        found = self.problems(self.text.replace(clip, clip + ' assert(tNear == tNear);'))
        self.assertTrue(any('<<Clip the parametric interval to slab i>> holds the book'
                            in p for p in found), found)

    def test_no_new_chunk_uses_another_exercises_solution(self):
        extra = ('\n```cpp\n<<Mine>>=\nauto lrtText = std::string("x");\n'
                 '<<Widen tFar to cover rounding error>>\n@\n```\n')
        found = self.problems(self.text + extra)
        self.assertTrue(any('<<Mine>> uses <<Widen tFar' in p for p in found), found)

    def test_uses_are_read_as_noweb_reads_them(self):
        # A third red team's: `<<>>` first made the rest of the line one use
        # of a fragment named `>> <<Widen tFar...`, which holds no solution.
        extra = ('\n```cpp\n<<Mine>>=\nauto lrtText = std::string("x");\n'
                 '<<>> <<Widen tFar to cover rounding error>>\n@\n```\n')
        found = self.problems(self.text + extra)
        self.assertTrue(any('<<Mine>> uses <<Widen tFar' in p for p in found), found)

    def test_no_book_chunk_comes_to_use_another_exercises_solution(self):
        # A red team's: a chunk that holds no solution wraps one in brackets
        # of its own, an assert's argument, whose text would be in the binary.
        report = '<<Report the parametric interval of the hit>>='
        self.assertIn(report, self.text)
        found = self.problems(self.text.replace(report, report + '\nassert([&] {\n'
                                                '<<Widen tFar to cover rounding error>>\n'
                                                'return true; }());'))
        self.assertTrue(any('<<Report the parametric interval of the hit>> uses <<Widen tFar'
                            in p for p in found), found)


class CompileLeakTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix='lrt-compile-wall-')
        cls.copy = os.path.join(cls.tmp, 'repo')
        tg.copy_book(tg.ROOT, cls.copy)
        chapter = tg.read(os.path.join(tg.ROOT, tg.CHAPTER))
        cls.subs = os.path.join(cls.tmp, 'subs')
        for name, (_, attack) in ATTACKS.items():
            tg.put_chapter(cls.subs, name, attack(chapter))
        tg.put_chapter(cls.subs, 'solution', chapter)
        cls.no_bwrap = tg.failing_bwrap(os.path.join(cls.tmp, 'no-bwrap'))
        # What no grading of an exercise may show: every line of the book's
        # solutions but that exercise's own, long enough to be told from
        # ordinary code, and not in the book's code outside the regions.
        paths = sorted(glob.glob(os.path.join(tg.ROOT, 'chapters', '0[2-5]-*.md')))
        book = markup.Book(paths, tests=False)
        cls.owner = {f: e.id for c in book.chapters for e in c.exercises for f in e.fragments}
        public = set()
        for c in book.chapters:
            inside = {r.line(i) for r in c.regions for i in range(r.begin, r.end + 1)}
            public |= {t.strip() for k in c.chunks for i, t in enumerate(k.body)
                       if k.line + 1 + i not in inside}
        cls.secrets = {e: sorted({t.strip() for c in book.chapters for r in c.regions
                                  if cls.owner.get(r.chunk.name) != e
                                  for _, t in r.solution if len(t.strip()) >= 16} - public)
                       for e in set(cls.owner.values())}
        assert any('gamma(3)' in s for s in cls.secrets[cls.owner[tg.F9]])

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def grade(self, mode, fallback):
        out = os.path.join(self.tmp, 'out-' + mode.replace(' ', '-'))
        env = dict(os.environ, PYTHONDONTWRITEBYTECODE='1')
        if fallback:
            env['PATH'] = self.no_bwrap + os.pathsep + env['PATH']
        proc = subprocess.run(
            [sys.executable, os.path.join(self.copy, 'tools', 'grading', 'grade.py'), '--batch',
             self.subs, '--out', out, '--chapters', '05', '--cache',
             os.path.join(self.tmp, 'cache-' + mode.replace(' ', '-')),
             '--time-limit', str(tg.TIME_LIMIT)],
            cwd=self.copy, env=env, capture_output=True, text=True)
        self.assertEqual(proc.returncode, 0, proc.stdout + proc.stderr)
        everyone = set.intersection(*map(set, self.secrets.values()))
        for secret in everyone:
            self.assertNotIn(secret, proc.stdout + proc.stderr)
        for name, (fragment, _) in ATTACKS.items():
            attacked = self.owner[fragment]
            shown = ''
            for top, _, files in os.walk(os.path.join(out, name)):
                for file in files:
                    shown += tg.read(os.path.join(top, file))
            for secret in self.secrets[attacked]:
                self.assertNotIn(secret, shown, 'the book\'s solution leaked to %s (%s)'
                                 % (name, mode))
            results = read_json(os.path.join(out, name, 'results.json'))
            self.assertIn(mode, results['output'])
            for test in results['tests']:
                ex = test['name'].split()[0]
                if ex == attacked:
                    self.assertEqual(test['status'], 'failed', (name, test['name']))
                    self.assertIn('COMPILE-ERROR', test['output'], (name, test['name']))
                else:
                    self.assertEqual(test['status'], 'passed', (name, test['name']))
        diagnostic = tg.read(os.path.join(out, 'diagnostic', 'results.txt'))
        self.assertIn('error in the book\'s code of another exercise, which is not shown',
                      diagnostic)
        solution = read_json(os.path.join(out, 'solution', 'results.json'))
        self.assertAlmostEqual(solution['score'], solution['max_score'], places=3)

    @unittest.skipUnless(os.geteuid() == 0, 'the sandbox drops to its own user only as root')
    def test_bubblewrap(self):
        self.grade('bubblewrap', fallback=False)

    @unittest.skipUnless(os.geteuid() == 0, 'the fallback needs root')
    def test_fallback_without_namespaces(self):
        self.grade('unprivileged user', fallback=True)


@unittest.skipUnless(os.geteuid() == 0, 'only a root grader has a user to drop to')
class CompileUserTest(unittest.TestCase):
    """A compile of a student's code runs as the sandbox's unprivileged user,
    in a directory of that user's, never as root: in both modes."""

    def compile_as(self, fallback):
        tmp = tempfile.mkdtemp(prefix='lrt-compile-uid-')
        self.addCleanup(shutil.rmtree, tmp, ignore_errors=True)
        env = dict(os.environ)
        if fallback:
            env['PATH'] = tg.failing_bwrap(os.path.join(tmp, 'no-bwrap')) + os.pathsep + \
                env['PATH']
        # The grader's cache lies where only root may enter, as a test's does.
        os.chmod(tmp, 0o700)
        code = ('import os, sys; sys.path.insert(0, %r); from tools.grading import sandbox, build as grade_build\n'
                'print(sandbox.isolation())\n'
                'work = sandbox.compile_dir("uid-", %r)\n'
                'sandbox.hand_over(work)\n'
                'cache = sandbox.compile_cache(os.path.join(%r, "ccache"))\n'
                'cmd, cwd = sandbox.compile_command(\n'
                '    ["sh", "-c", "id -u; touch made"], work, cache)\n'
                'code, out = grade_build.run(cmd, cwd)\n'
                'print(code, out.split()[0], os.stat(os.path.join(work, "made")).st_uid,'
                ' sandbox.sandbox_uid())\n'
                'import shutil; shutil.rmtree(work)\n' % (tg.ROOT, tmp, tmp))
        proc = subprocess.run([sys.executable, '-c', code], env=env, capture_output=True,
                              text=True)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        mode, rest = proc.stdout.split('\n', 1)
        self.assertEqual(mode, 'unprivileged user' if fallback else 'bubblewrap')
        status, ran_as, owner, uid = map(int, rest.split())
        self.assertEqual(status, 0, proc.stdout)
        self.assertNotEqual(ran_as, 0)
        self.assertEqual((ran_as, owner), (uid, uid))

    def test_bubblewrap(self):
        self.compile_as(fallback=False)

    def test_fallback_without_namespaces(self):
        self.compile_as(fallback=True)


if __name__ == '__main__':
    unittest.main()
