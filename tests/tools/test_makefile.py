"""Tests of the Makefile's front door: every command the README gives checks
Debian's packages (tools/deps.sh) before it runs anything else, so that it
works as the first command on a fresh machine; and a build prints one short
line per step unless asked for the commands in full (V=1)."""
import os
import glob
import json
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

# Run from make test, the environment holds the outer make's flags and its
# exported variables: none may reach these makes.
ENV = {k: v for k, v in os.environ.items() if k not in (
    'MAKEFLAGS', 'MFLAGS', 'MAKELEVEL', 'CHAPTERS', 'BUILD', 'FLOAT', 'SANITIZE', 'V')}


def readme_make_commands():
    """Every make command of the README: its two commands and each row of its
    table of targets, with the optional parts ([...]) left out and names
    given for the paths it leaves to the reader."""
    with open(os.path.join(ROOT, 'README.md'), encoding='utf-8') as f:
        text = f.read()
    commands = re.findall(r'^    (make(?: \w+)?)\s+#', text, re.M)
    commands += re.findall(r'^\| `(make [^`]*)`', text, re.M)
    return [re.sub(r'\s*\[.*\]', '', c) for c in commands]


def first_command(command, build):
    """The first command that `make -n` prints for a README command. make -n
    still runs the rules that remake its makefiles (which is where the
    package check stands) and the lines that run make again; the process is
    stopped once the line is read, before anything else can run."""
    words = shlex.split(command)
    proc = subprocess.Popen(words[:1] + ['-n', '--no-print-directory', 'BUILD=' + build] +
                            words[1:], cwd=ROOT, env=ENV, stdout=subprocess.PIPE,
                            stderr=subprocess.DEVNULL, text=True, start_new_session=True)
    try:
        for line in proc.stdout:
            if line.strip():
                return line.strip()
        return ''
    finally:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
        proc.stdout.close()


class PackagesFirstTest(unittest.TestCase):
    def setUp(self):
        self.build = tempfile.mkdtemp(prefix='lrt-makefile-test-')
        self.addCleanup(shutil.rmtree, self.build)

    @unittest.skipIf(os.path.exists(os.path.join(ROOT, 'exercises.json')),
                     'a kit: its README names only make and make test')
    def test_readme_lists_the_commands_checked_here(self):
        # The README's reading is itself checked: its two commands and the
        # targets that the fresh-machine issue named are all among them.
        targets = {c.split()[1] if len(c.split()) > 1 else 'all'
                   for c in readme_make_commands()}
        for target in ('all', 'test', 'html', 'exercises', 'grade', 'gradescope', 'bench',
                       'try-exercises'):
            self.assertIn(target, targets)

    def test_every_readme_command_checks_the_packages_first(self):
        for command in readme_make_commands():
            first = first_command(command, self.build)
            # The grading commands check the smaller set a grading image
            # needs, make book-measurements the larger one it needs
            # (valgrind).
            expected = 'measure' if 'book-measurements' in command else \
                'grade' if re.match(r'make (grade|gradescope)', command) else None
            self.assertEqual(first, 'tools/deps.sh' + (' ' + expected if expected else ''),
                             command)

    def test_make_clean_needs_no_package(self):
        self.assertTrue(first_command('make clean', self.build).startswith('rm -rf'))


CHAPTERS = ' '.join(sorted(os.path.relpath(p, ROOT)
                           for p in glob.glob(os.path.join(ROOT, 'chapters', '[0-9][0-9]-*.md'))))


class ShortLinesTest(unittest.TestCase):
    """The code as of chapter 2 built into a scratch directory, once in each
    form of output; ccache makes the second build cheap."""

    def build(self, *extra):
        build = tempfile.mkdtemp(prefix='lrt-makefile-test-')
        self.addCleanup(shutil.rmtree, build)
        output = ''
        for goal in ('tangle', 'lib'):
            result = subprocess.run(['make', '--no-print-directory', '-f', 'tools/make/asof.mk',
                                     'ASOF=02', 'BUILD=' + build, 'CHAPTERS=' + CHAPTERS, goal] +
                                    list(extra),
                                    cwd=ROOT, env=ENV, capture_output=True, text=True)
            self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
            output += result.stdout
        return build, output.splitlines()

    def test_one_short_line_per_step_by_default(self):
        build, lines = self.build()
        src = os.path.join(build, 'float/asof/02/src')
        compiled = sorted(os.path.relpath(os.path.join(d, f), src)
                          for d, _, files in os.walk(src) for f in files if f.endswith('.cpp'))
        self.assertTrue(compiled)
        expected = (['TANGLE %s (the code as of chapter 2)' % src] +
                    ['CXX    %s (as of chapter 2)' % path for path in compiled] +
                    ['AR     liblrt.a (as of chapter 2)'])
        self.assertEqual(sorted(lines), sorted(expected))

    def test_v1_prints_the_commands_in_full(self):
        _, lines = self.build('V=1')
        self.assertFalse([l for l in lines if re.match(r'^(TANGLE|CXX|AR) ', l)], lines)
        self.assertTrue([l for l in lines if 'tools/noweb/tangle.py --line-directives' in l], lines)
        self.assertTrue([l for l in lines if re.search(r'\bg\+\+ .* -c src/lrt/\S+\.cpp', l)],
                        lines)
        self.assertTrue([l for l in lines if l.startswith('ar rcs ')], lines)



def build_compile(line):
    """A compile command of the build (tools/make/asof.mk, as make -n prints
    it) without what only the build needs: the directory and ccache before
    the compiler, the dependency file, the prefix map of the debugging
    information, the object's path and what follows a failure (||). Paths
    are named as from the
    repository's root: src/ is the tangle, pch/ the precompiled header."""
    words = shlex.split(line.split(' && ', 1)[1].split(' || ', 1)[0])
    while '=' in words[0] or os.path.basename(words[0]) == 'ccache':
        words.pop(0)
    kept, dropped = [], {'-MT': 2, '-o': 2, '-MD': 1, '-MP': 1}
    while words:
        word = words.pop(0)
        if word in dropped:
            del words[:dropped[word] - 1]
        elif not word.startswith('-fdebug-prefix-map='):
            kept.append(word)
    return [re.sub(r'^(-I)?src(/|$)', r'\1tangled\2', w)
            .replace('pch/test_pch.h', 'tools/compile/test_pch.h') for w in kept]


class CompileCommandsTest(unittest.TestCase):
    """compile_commands.json, as the Makefile writes it, compiles a file of
    the library and a test as the build does, so that an IDE sees the same
    flags (-ffp-contract=off, the tests' level, the precompiled header's
    includes)."""

    def test_compile_commands_are_the_builds(self):
        build = tempfile.mkdtemp(prefix='lrt-makefile-test-')
        self.addCleanup(shutil.rmtree, build)
        last = os.path.basename(CHAPTERS.split()[-1])[:2]
        asof = ['make', '--no-print-directory', '-f', 'tools/make/asof.mk', 'ASOF=' + last,
                'BUILD=' + build, 'CHAPTERS=' + CHAPTERS]
        subprocess.run(asof + ['tangle'], cwd=ROOT, env=ENV, check=True, capture_output=True)
        planned = subprocess.run(asof + ['-n', '-B', 'lib', 'tests'], cwd=ROOT, env=ENV,
                                 check=True, capture_output=True, text=True).stdout
        compiles = [build_compile(l) for l in planned.splitlines() if ' -c ' in l and ' && ' in l]
        # The Makefile's own rule, as make -n shows it (the make it runs,
        # then what that make runs), run with its output here.
        command = 'make -n --no-print-directory BUILD=%s compile_commands.json' % build
        for step in ('compile-commands', 'compile_commands.py'):
            shown = subprocess.run(command, shell=True, cwd=ROOT, env=dict(ENV, BUILD=build),
                                   check=True, capture_output=True, text=True).stdout
            lines = [l for l in re.sub(r'\\\n\s*', ' ', shown).splitlines() if step in l]
            self.assertEqual(len(lines), 1, shown)
            command = lines[0] + ' -n'
        written = subprocess.run(lines[0].rsplit(' > ', 1)[0], shell=True, cwd=ROOT,
                                 env=ENV, check=True, capture_output=True, text=True).stdout
        entries = {e['file']: e for e in json.loads(written)}
        for kind in ('tangled/lrt/', 'tests/ch'):
            with self.subTest(kind=kind):
                compile = next(c for c in compiles if c[-1].startswith(kind))
                entry = entries[compile[-1]]
                self.assertEqual(entry['directory'], ROOT)
                self.assertEqual(entry['arguments'], compile)



class CompileFlagsTest(unittest.TestCase):
    """tools/compile/flags.py, which the grader reads the compiler and its
    flags with, reads tools/compile/flags.mk as make does."""

    def test_python_reads_every_variable_as_make_does(self):
        sys.path.insert(0, ROOT)
        from tools.compile import flags
        names = sorted(flags.definitions())
        self.assertIn('WORKER_CXXFLAGS', names)
        shown = subprocess.run(
            ['make', '-s', '--no-print-directory', '-f', 'tools/compile/flags.mk', '--eval',
             'show: ; @:$(foreach v,%s,$(info $(v)=$($(v))))' % ' '.join(names), 'show'],
            cwd=ROOT, env={k: v for k, v in ENV.items() if k not in names},
            check=True, capture_output=True, text=True).stdout
        self.assertEqual(shown.splitlines(), ['%s=%s' % (n, flags.value(n)) for n in names])


if __name__ == '__main__':
    unittest.main()
