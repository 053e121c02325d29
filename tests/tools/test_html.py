"""Tests of the web edition (make html) in a real browser: Debian's chromium,
driven by chromedriver through python3-selenium, headless and offline.

The site is built once (make html, which changes nothing when it is up to
date) and every page is opened from the file system: it must load with no
console message and no failed request, with every image loaded and all its
mathematics typeset by MathJax (no raw $$ or \\( left); every internal link
and every fragment's anchor must resolve. Clicking a fragment use must
reach its definition, on its page; the search must find a fragment by a
word of its name. Screenshots of the most code-heavy and the most
equation-heavy page, at a desktop's and a phone's width, are kept in
build/html-screenshots/. (That the student edition's web pages hold no
solution is tested with the other kits, in test_exercises.py.)
"""
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import unittest
import urllib.parse

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
TOOLS = os.path.join(ROOT, 'tools')
SITE = os.path.join(ROOT, 'build', 'html')
SHOTS = os.path.join(ROOT, 'build', 'html-screenshots')

try:
    import selenium  # noqa: F401
except ImportError:
    # python3-selenium installs into Debian's own Python; a python3 of
    # another origin (pyenv, say) finds it there.
    sys.path.append('/usr/lib/python3/dist-packages')
from selenium import webdriver  # noqa: E402
from selenium.webdriver.chrome.service import Service  # noqa: E402

CHROMIUM = '/usr/bin/chromium'
CHROMEDRIVER = '/usr/bin/chromedriver'
# The network is closed here: nothing may try to reach it.
CHROMIUM_FLAGS = ('--headless', '--no-sandbox', '--disable-gpu', '--disable-quic',
                  '--no-first-run', '--disable-background-networking',
                  '--disable-component-update', '--disable-sync',
                  '--disable-default-apps', '--disable-extensions')
DESKTOP = (1280, 900)
PHONE = (390, 844)
MATH_TIMEOUT = 120  # seconds for MathJax on one page, on a loaded machine
MAKE_ENV_DROP = ('MAKEFLAGS', 'MFLAGS', 'MAKELEVEL', 'MAKEOVERRIDES', 'CHAPTERS', 'BUILD',
                 'CH', 'UPTO', 'ONLY', 'ASOF')

browser = None
profile = None


def setUpModule():
    global browser, profile
    env = {k: v for k, v in os.environ.items() if k not in MAKE_ENV_DROP}
    proc = subprocess.run(['make', '--no-print-directory', 'html'], cwd=ROOT, env=env,
                          capture_output=True, text=True)
    if proc.returncode != 0:
        raise RuntimeError('make html failed:\n' + (proc.stdout + proc.stderr)[-4000:])
    profile = tempfile.mkdtemp(prefix='lrt-chromium-')
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in CHROMIUM_FLAGS:
        options.add_argument(flag)
    options.add_argument('--user-data-dir=' + profile)
    options.add_argument('--window-size=%d,%d' % DESKTOP)
    options.set_capability('goog:loggingPrefs', {'browser': 'ALL', 'performance': 'ALL'})
    browser = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    browser.set_page_load_timeout(MATH_TIMEOUT)


def tearDownModule():
    if browser:
        browser.quit()
    if profile:
        shutil.rmtree(profile, ignore_errors=True)


def url(page):
    return 'file://' + os.path.join(SITE, page)


def pages():
    return sorted(os.path.basename(p) for p in glob.glob(os.path.join(SITE, '*.html')))


def set_viewport(size):
    width, height = size
    browser.execute_cdp_cmd('Emulation.setDeviceMetricsOverride', {
        'width': width, 'height': height, 'deviceScaleFactor': 1,
        'mobile': width < 600})


def open_page(target):
    """Loads a page and waits until MathJax has finished with it."""
    browser.get(url(target) if '://' not in target else target)
    started = time.time()
    while not browser.execute_script(
            'return document.documentElement.getAttribute("data-math")'):
        if time.time() - started > MATH_TIMEOUT:
            raise AssertionError('%s: MathJax did not finish in %d s' % (target,
                                                                        MATH_TIMEOUT))
        time.sleep(0.05)


def problems_logged():
    """Console messages, and requests that failed, since the last call."""
    found = ['console %s: %s' % (e['level'], e['message'])
             for e in browser.get_log('browser')]
    for entry in browser.get_log('performance'):
        message = json.loads(entry['message'])['message']
        if message['method'] == 'Network.loadingFailed':
            found.append('failed request: %s' % message['params'].get('errorText'))
        elif message['method'] == 'Network.requestWillBeSent':
            request = message['params']['request']['url']
            if not request.startswith(('file://', 'data:')):
                found.append('request leaves the site: %s' % request)
    return found


# What each page reports about itself, from inside the browser.
PAGE_REPORT = r'''
var raw = [];
var walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT, {
  acceptNode: function (node) {
    return node.parentElement.closest('script, style, pre, code') ?
      NodeFilter.FILTER_REJECT : NodeFilter.FILTER_ACCEPT;
  }});
while (walker.nextNode()) {
  var text = walker.currentNode.nodeValue;
  if (/\$\$|\\\(|\\\)|\\\[|\\\]/.test(text)) raw.push(text.trim().slice(0, 100));
}
var untypeset = Array.from(document.querySelectorAll('span.math')).filter(function (s) {
  return !s.querySelector('script[type^="math/tex"]');
}).map(function (s) { return s.textContent.slice(0, 100); });
var images = Array.from(document.images).filter(function (i) {
  return !i.complete || i.naturalWidth === 0;
}).map(function (i) { return i.getAttribute('src'); });
// The web fonts that the page declares (MathJax's, once it has run): the
// first url() of each is what a browser without the fonts installed loads.
var fonts = [];
Array.from(document.styleSheets).forEach(function (sheet) {
  var rules;
  try { rules = sheet.cssRules; } catch (e) { return; }
  Array.from(rules).forEach(function (rule) {
    if (rule.type !== CSSRule.FONT_FACE_RULE) return;
    var first = /url\(["']?([^"')]+)/.exec(rule.style.getPropertyValue('src'));
    if (first) fonts.push(new URL(first[1], sheet.href || document.baseURI).href);
  });
});
return {
  raw: raw, untypeset: untypeset, images: images, count: document.images.length,
  ids: Array.from(document.querySelectorAll('[id]')).map(function (e) { return e.id; }),
  links: Array.from(document.querySelectorAll('a[href]')).map(function (a) { return a.href; }),
  fragments: Array.from(document.querySelectorAll('.fragment[id]')).map(function (e) {
    return e.id; }),
  math: document.querySelectorAll('span.math').length, fonts: fonts
};
'''


class SiteTest(unittest.TestCase):
    """Every page, opened one after the other, then every link among them."""

    @classmethod
    def setUpClass(cls):
        set_viewport(DESKTOP)
        problems_logged()
        cls.reports, cls.problems = {}, []
        for page in pages():
            open_page(page)
            cls.reports[page] = browser.execute_script(PAGE_REPORT)
            cls.problems += ['%s: %s' % (page, p) for p in problems_logged()]

    def test_the_site_has_its_pages(self):
        self.assertIn('index.html', self.reports)
        self.assertIn('index-of-fragments.html', self.reports)
        self.assertIn('index-of-identifiers.html', self.reports)
        self.assertGreater(len(self.reports), 20)

    def test_pages_load_without_errors_or_failed_requests(self):
        self.assertEqual(self.problems, [])

    def test_mathematics_is_typeset(self):
        left = ['%s: %s' % (page, text) for page, r in self.reports.items()
                for text in r['raw'] + r['untypeset']]
        self.assertEqual(left, [])
        self.assertGreater(sum(r['math'] for r in self.reports.values()), 100)

    def test_images_load(self):
        broken = ['%s: %s' % (page, src) for page, r in self.reports.items()
                  for src in r['images']]
        self.assertEqual(broken, [])
        self.assertGreater(sum(r['count'] for r in self.reports.values()), 10)

    def test_web_fonts_are_in_the_site(self):
        # Chromium here finds MathJax's fonts installed (fonts-mathjax), so it
        # never asks for the site's copies; a reader's browser may.
        fonts = {font for r in self.reports.values() for font in r['fonts']}
        paths = {f: urllib.parse.unquote(urllib.parse.urlsplit(f).path) for f in fonts}
        missing = [f for f, path in paths.items()
                   if not path.startswith(SITE + os.sep) or not os.path.isfile(path)]
        self.assertEqual(missing, [])
        self.assertTrue(any(f.endswith('.woff') for f in fonts), fonts)

    def test_internal_links_resolve(self):
        ids = {page: set(r['ids']) for page, r in self.reports.items()}
        broken, checked = [], 0
        for page, r in self.reports.items():
            for link in r['links']:
                parts = urllib.parse.urlsplit(link)
                if parts.scheme in ('http', 'https', 'mailto'):
                    continue
                self.assertEqual(parts.scheme, 'file', link)
                path = urllib.parse.unquote(parts.path)
                target = os.path.relpath(path, SITE)
                checked += 1
                if target not in ids:
                    broken.append('%s: %s (no such page)' % (page, link))
                elif parts.fragment and urllib.parse.unquote(parts.fragment) not in ids[target]:
                    broken.append('%s: %s (no such anchor)' % (page, link))
        self.assertEqual(broken, [])
        self.assertGreater(checked, 1000)

    def test_every_fragment_has_an_anchor_that_the_index_reaches(self):
        anchors = {f for r in self.reports.values() for f in r['fragments']}
        self.assertTrue(all(re.match(r'^chunk:(\d+|[A-Z])\.\d+$', a) for a in anchors), anchors)
        # The appendix's fragments are numbered A.1, ... as in the PDF.
        self.assertTrue(any(a.startswith('chunk:A.') for a in anchors))
        indexed = {urllib.parse.unquote(urllib.parse.urlsplit(link).fragment)
                   for link in self.reports['index-of-fragments.html']['links']}
        self.assertEqual(anchors - indexed, set())
        self.assertGreater(len(anchors), 100)


class InteractionTest(unittest.TestCase):
    def setUp(self):
        set_viewport(DESKTOP)

    def assertAtFragment(self, anchor, name):
        """The page shows fragment anchor, whose header names name, in view."""
        state = browser.execute_script('''
            var e = document.getElementById(decodeURIComponent(location.hash.slice(1)));
            if (!e) return null;
            var r = e.getBoundingClientRect(), page = document.documentElement;
            return {id: e.id, top: r.top, height: window.innerHeight,
                    bottom: window.scrollY + window.innerHeight >= page.scrollHeight - 1,
                    name: e.querySelector('.fragname').textContent};''')
        self.assertIsNotNone(state, browser.current_url)
        self.assertEqual(state['id'], anchor)
        self.assertEqual(state['name'], '⟨%s⟩' % name)
        # At the top of the window, or as near as the end of the page allows.
        self.assertGreaterEqual(state['top'], -1)
        self.assertLess(state['top'], state['height'] - 30)
        self.assertTrue(state['top'] < 60 or state['bottom'], state)

    def click_use(self, page, other_page):
        """Clicks the first use on page whose definition is (or is not) on
        another page; returns its anchor and fragment name."""
        open_page(page)
        uses = browser.find_elements('css selector', 'a.fraguse')
        for use in uses:
            target = urllib.parse.urlsplit(use.get_attribute('href'))
            elsewhere = os.path.basename(urllib.parse.unquote(target.path)) != page
            if elsewhere == other_page:
                anchor = urllib.parse.unquote(target.fragment)
                name = use.find_element('css selector', '.fragusename').text
                browser.execute_script('arguments[0].scrollIntoView({block: "center"})', use)
                use.click()
                return anchor, name
        self.fail('%s has no fragment use defined %s' % (
            page, 'on another page' if other_page else 'on the same page'))

    def test_clicking_a_use_opens_the_page_of_its_definition(self):
        anchor, name = self.click_use('05-slab-code.html', other_page=True)
        self.assertAtFragment(anchor, name)
        self.assertNotIn('05-slab-code.html', browser.current_url)

    def test_clicking_a_use_scrolls_to_its_definition(self):
        anchor, name = self.click_use('05-slab-code.html', other_page=False)
        self.assertIn('05-slab-code.html#', browser.current_url)
        self.assertAtFragment(anchor, name)

    def search(self, text):
        box = browser.find_element('id', 'search')
        box.clear()
        box.send_keys(text)
        return [(a.get_attribute('href'), a.find_element('css selector', '.name').text)
                for a in browser.find_elements('css selector', '#search-results a')]

    def test_search_finds_a_fragment_by_a_word_of_its_name(self):
        # A word that only one fragment's name contains, chosen from the
        # index itself, so that the test follows the book.
        with open(os.path.join(SITE, 'search-index.js'), encoding='utf-8') as f:
            index = json.loads(f.read().split('=', 1)[1].strip().rstrip(';'))
        names = [e for e in index if e['k'] == 'f']
        counts = {}
        for e in names:
            for word in set(re.findall(r'[a-z]{6,}', e['t'].lower())):
                counts[word] = counts.get(word, 0) + 1
        word = min(w for w, c in counts.items() if c == 1)
        entry = next(e for e in names if word in e['t'].lower())
        open_page('index.html')
        results = self.search(word.capitalize())
        self.assertIn('⟨%s⟩' % entry['t'], [name for _, name in results])
        link = next(a for a in browser.find_elements('css selector', '#search-results a')
                    if a.find_element('css selector', '.name').text == '⟨%s⟩' % entry['t'])
        link.click()
        self.assertAtFragment(urllib.parse.unquote(entry['u'].split('#', 1)[1]), entry['t'])

    def test_search_finds_identifiers_and_sections(self):
        open_page('index.html')
        results = self.search('intersectp')
        self.assertIn('IntersectP', [name for _, name in results])
        results = self.search('slab test')
        self.assertIn('The Slab Test', [name for _, name in results])
        self.assertEqual(self.search('qqqxyzzy'), [])

    def test_side_bar_folds_on_a_phone(self):
        set_viewport(PHONE)
        open_page('05-slab-code.html')
        sidebar = browser.find_element('id', 'sidebar')
        self.assertFalse(self.visible(sidebar))
        browser.find_element('css selector', '.navtoggle').click()
        time.sleep(0.3)   # the side bar slides in
        self.assertTrue(self.visible(sidebar))
        # Nothing but code and wide equations may need a sideways scroll.
        width = browser.execute_script(
            'return [document.documentElement.scrollWidth, window.innerWidth]')
        self.assertLessEqual(width[0], width[1])

    @staticmethod
    def visible(element):
        return browser.execute_script(
            'var r = arguments[0].getBoundingClientRect(); return r.right > 0;', element)


def heaviest(pattern):
    """The page with the most matches of pattern."""
    def count(page):
        with open(os.path.join(SITE, page), encoding='utf-8') as f:
            return len(re.findall(pattern, f.read()))
    return max(pages(), key=count)


class ScreenshotTest(unittest.TestCase):
    """Screenshots kept for people to look at, and a check that each page
    fits the width of the screen."""

    def test_screenshots(self):
        os.makedirs(SHOTS, exist_ok=True)
        chosen = {'code': heaviest(r'<div class="fragment"'),
                  'equations': heaviest(r'class="math display"')}
        taken = []
        for kind, page in chosen.items():
            first = '.fragment' if kind == 'code' else '.math.display'
            for label, size in (('desktop', DESKTOP), ('phone', PHONE)):
                set_viewport(size)
                open_page(page)
                browser.execute_script(
                    'document.querySelector(arguments[0]).scrollIntoView({block: "start"});'
                    'window.scrollBy(0, -60);', first)
                path = os.path.join(SHOTS, '%s-%s-%s.png' % (kind, label,
                                                            page[:-len('.html')]))
                self.assertTrue(browser.save_screenshot(path))
                taken.append(path)
                overflow = browser.execute_script(
                    'return document.documentElement.scrollWidth - window.innerWidth')
                self.assertLessEqual(overflow, 0, '%s at %s' % (page, label))
        set_viewport(DESKTOP)
        for path in taken:
            self.assertGreater(os.path.getsize(path), 10000, path)


if __name__ == '__main__':
    unittest.main()
