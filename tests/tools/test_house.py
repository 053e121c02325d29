"""The layout of tools/ as docs/architecture.md and the README describe it:
small files, one folder per job, and maps that name every folder. A tool
added where no map names it, or a file grown past what one reading takes in,
fails here rather than going unnoticed."""
import ast
import os
import subprocess
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
TOOLS = os.path.join(ROOT, 'tools')
MAX_LINES = 500


def tracked(prefix):
    out = subprocess.run(['git', 'ls-files', prefix], cwd=ROOT, capture_output=True,
                         text=True)
    if out.returncode != 0:
        raise unittest.SkipTest('not a git checkout')
    return out.stdout.split()


def folders():
    return sorted(d for d in os.listdir(TOOLS)
                  if os.path.isdir(os.path.join(TOOLS, d)) and d != '__pycache__')


class HouseTest(unittest.TestCase):
    def test_no_file_of_tools_is_longer_than_500_lines(self):
        long = []
        for path in tracked('tools'):
            with open(os.path.join(ROOT, path), 'rb') as f:
                lines = f.read().count(b'\n')
            if lines > MAX_LINES:
                long.append('%s: %d lines' % (path, lines))
        self.assertEqual(long, [], 'split these along their jobs')

    def test_every_python_folder_says_what_it_holds(self):
        for folder in folders():
            if not any(f.endswith('.py') for f in os.listdir(os.path.join(TOOLS, folder))):
                continue  # make/: the maps below describe it
            init = os.path.join(TOOLS, folder, '__init__.py')
            self.assertTrue(os.path.exists(init), init)
            with open(init) as f:
                self.assertTrue(ast.get_docstring(ast.parse(f.read())),
                                '%s has no docstring' % init)

    def test_the_maps_name_every_folder(self):
        for doc in ('README.md', os.path.join('docs', 'architecture.md')):
            with open(os.path.join(ROOT, doc)) as f:
                text = f.read()
            for folder in folders():
                self.assertIn('`tools/%s/`' % folder, text, doc)


if __name__ == '__main__':
    unittest.main()
