#!/usr/bin/env python3
"""The web edition of the book: a static site, one page per section.

    tools/book/html_site.py --out DIR [--cache DIR] BOOK.md CHAPTER.md...

pandoc reads the book with tools/book/exercises.lua and tools/book/html.lua (which
typesets fragments, numbers, figures and cross-references, and decides the
pages) and citeproc, and writes one HTML body. This script cuts it into the
pages that html.lua marked, points every "#id" link at the page that holds id
(and fails on a link to an id that no page has, or on an id that two elements
share), and writes DIR: the pages, each with the contents as a side bar and
previous/next links; the search index (search-index.js); the figures (the
book's images, and its TikZ drawings compiled on their own to SVG); the
site's CSS and JavaScript (tools/book/web/) and MathJax, from Debian's
libjs-mathjax. Everything is local, so DIR works from the file system and on
any static host.

A drawing is compiled (pdflatex, then pdftocairo -svg) only when its LaTeX,
the drawings' preamble or a file it reads has changed: the SVG is kept in the
cache (default DIR-cache) under the hash of all three.

Run from the repository root, so that figure paths resolve as in the chapters.
"""
import argparse
import concurrent.futures
import hashlib
import html
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import urllib.parse

HERE = os.path.dirname(os.path.abspath(__file__))
WEB = os.path.join(HERE, 'web')
MATHJAX = '/usr/share/javascript/mathjax'
# The parts of MathJax that its TeX-AMS_CHTML configuration loads: the TeX
# input, the CommonHTML output with its web fonts, and the extensions.
MATHJAX_PARTS = ('MathJax.js', 'config/TeX-AMS_CHTML.js', 'extensions', 'jax/input/TeX',
                 'jax/output/CommonHTML', 'jax/element', 'fonts/HTML-CSS/TeX/woff',
                 'localization/en')
PAGE_MARK = re.compile(r'<!--lrt-page (\S+)-->\n?')
MANIFEST = re.compile(r'<script type="application/json" id="lrt-manifest">(.*?)</script>\n?',
                      re.S)
ID = re.compile(r'\sid="([^"]*)"')
HREF = re.compile(r'href="#([^"]*)"')
KIND_NAMES = {'s': 'Section', 'f': 'Fragment', 'i': 'Identifier'}


def fail(message):
    sys.exit('html: ' + message)


def read(path):
    with open(path, encoding='utf-8') as f:
        return f.read()


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'w', encoding='utf-8') as f:
        f.write(text)


# ---------------------------------------------------------------------------
# pandoc

def run_pandoc(inputs):
    cmd = ['pandoc'] + inputs + [
        '--from', 'markdown', '--lua-filter', os.path.join(HERE, 'measured.lua'),
        '--lua-filter', os.path.join(HERE, 'exercises.lua'),
        '--lua-filter', os.path.join(HERE, 'html.lua'), '--citeproc', '--mathjax',
        '--to', 'html5']
    proc = subprocess.run(cmd, capture_output=True, text=True)
    sys.stderr.write(proc.stderr)
    if proc.returncode != 0:
        fail('pandoc failed')
    # citeproc only warns about a key that the bibliography lacks.
    if re.search(r'Citeproc: citation .* not found', proc.stderr):
        fail('citations of keys that the bibliography does not have')
    return proc.stdout


def split(body):
    match = MANIFEST.search(body)
    if not match:
        fail('pandoc wrote no manifest (was tools/book/html.lua run?)')
    manifest = json.loads(match.group(1))
    body = body[:match.start()] + body[match.end():]
    parts = PAGE_MARK.split(body)
    if parts[0].strip():
        fail('text before the first page: %r' % parts[0][:200])
    pages = dict(zip(parts[1::2], parts[2::2]))
    files = [p['file'] for p in manifest['pages']]
    if list(pages) != files:
        fail('the pages in the text are not the pages of the manifest')
    return manifest, pages


# ---------------------------------------------------------------------------
# Links

def link_targets(pages):
    """id -> the page that holds it; fails on an id used twice."""
    where = {}
    for name, text in pages.items():
        for match in ID.finditer(text):
            key = html.unescape(match.group(1))
            if key in where:
                fail('two elements have the id %r (%s and %s)' % (key, where[key], name))
            where[key] = name
    return where


def relink(pages, where):
    """Points each "#id" at the page that holds id."""
    broken = []
    for name, text in pages.items():
        def target(match):
            key = html.unescape(urllib.parse.unquote(match.group(1)))
            page = where.get(key)
            if page is None:
                broken.append('%s: #%s' % (name, key))
                return match.group(0)
            return match.group(0) if page == name else 'href="%s#%s"' % (page,
                                                                            match.group(1))
        pages[name] = HREF.sub(target, text)
    if broken:
        fail('links to ids that no page has:\n  ' + '\n  '.join(broken[:30]))


# ---------------------------------------------------------------------------
# Figures

FIGURE_TEX = r'''\documentclass[11pt%(width)s]{standalone}
\usepackage[T1]{fontenc}
\usepackage{lmodern}
\usepackage{amsmath}
%(preamble)s
%(textwidth)s\begin{document}
%(body)s
\end{document}
'''


def figure_source(figure, textwidth):
    preamble = read(os.path.join(HERE, 'tikz-preamble.tex'))
    return FIGURE_TEX % {
        'width': ',varwidth=' + textwidth if textwidth else ',varwidth',
        'preamble': preamble,
        'textwidth': (r'\setlength{\textwidth}{%s}\setlength{\linewidth}{\textwidth}' % textwidth
                      + '\n') if textwidth else '',
        'body': figure['latex'].strip()}


def figure_key(source):
    """The hash of a drawing's LaTeX and of the files it reads (figures/...)."""
    digest = hashlib.sha1(source.encode('utf-8'))
    for path in sorted(set(re.findall(r'figures/[\w./-]+', source))):
        if os.path.isfile(path):
            with open(path, 'rb') as f:
                digest.update(path.encode() + b'\0' + f.read())
    return digest.hexdigest()


def compile_figure(name, source, svg):
    with tempfile.TemporaryDirectory() as tmp:
        tex = os.path.join(tmp, name + '.tex')
        write(tex, source)
        proc = subprocess.run(['pdflatex', '-interaction=nonstopmode', '-halt-on-error',
                               '-output-directory', tmp, tex], capture_output=True, text=True)
        if proc.returncode != 0:
            log = proc.stdout
            at = log.find('\n!')
            fail('figure %s does not compile on its own:\n%s' % (
                name, log[at:at + 1200] if at >= 0 else log[-1200:]))
        pdf = os.path.join(tmp, name + '.pdf')
        proc = subprocess.run(['pdftocairo', '-svg', pdf, os.path.join(tmp, 'out.svg')],
                              capture_output=True, text=True)
        if proc.returncode != 0:
            fail('pdftocairo failed on figure %s: %s' % (name, proc.stderr))
        os.makedirs(os.path.dirname(svg), exist_ok=True)
        shutil.move(os.path.join(tmp, 'out.svg'), svg + '.part')
        os.replace(svg + '.part', svg)


def figures(manifest, cache, out):
    """Compiles the drawings that the cache lacks, in parallel; copies all."""
    jobs, compiled = [], 0
    for figure in manifest['figures']:
        source = figure_source(figure, manifest['textwidth'])
        svg = os.path.join(cache, figure_key(source) + '.svg')
        jobs.append((figure['name'], source, svg))
    missing = [job for job in jobs if not os.path.exists(job[2])]
    with concurrent.futures.ThreadPoolExecutor(os.cpu_count() or 1) as pool:
        for future in [pool.submit(compile_figure, *job) for job in missing]:
            future.result()
            compiled += 1
    for name, _, svg in jobs:
        target = os.path.join(out, 'figures', name + '.svg')
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(svg, target)
    return compiled


def images(pages, out):
    """Copies the images that pages show from figures/ (not the drawings)."""
    drawn = set()
    for text in pages.values():
        for src in re.findall(r'<img src="([^"]+)"', text):
            path = html.unescape(src)
            if path.endswith('.svg') or path in drawn:
                continue
            if not os.path.isfile(path):
                fail('an image that does not exist: %s' % path)
            target = os.path.join(out, path)
            os.makedirs(os.path.dirname(target), exist_ok=True)
            shutil.copyfile(path, target)
            drawn.add(path)


# ---------------------------------------------------------------------------
# Pages

def esc(text):
    return html.escape(text, quote=True)


def entry_title(page):
    """A page's title with its number; the front page is named by its first
    heading (the preface)."""
    number = '<span class="secnum">%s</span> ' % page['number'] if page['number'] else ''
    first = page['headings'][0]['title'] if page['headings'] else 'Title page'
    return number + (page['title'] or first)


def contents(manifest, current=None):
    """The contents as nested lists: chapters; the sections of the current
    chapter (all of them on the front page); the headings of the current page."""
    pages = manifest['pages']
    now = next((p for p in pages if p['file'] == current), None)
    full = current is None or (now and now['kind'] == 'front')
    out = ['<ol class="toc">']
    i = 0
    while i < len(pages):
        page = pages[i]
        j = i + 1
        while j < len(pages) and pages[j]['kind'] in ('section', 'subsection'):
            j += 1
        chapter = pages[i:j]
        here = any(p['file'] == current for p in chapter)
        cls = ' class="%s%s"' % (page['kind'], ' open' if here else '')
        out.append('<li%s>%s' % (cls, toc_link(page, current)))
        if len(chapter) > 1 and (full or here):
            out.append('<ol>')
            for k, section in enumerate(chapter[1:], 1):
                if section['kind'] == 'subsection':
                    continue
                out.append('<li>' + toc_link(section, current))
                subs = []
                for sub in chapter[k + 1:]:
                    if sub['kind'] != 'subsection':
                        break
                    subs.append('<li>' + toc_link(sub, current) + '</li>')
                if subs:
                    out.append('<ol>' + ''.join(subs) + '</ol>')
                out.append('</li>')
            out.append('</ol>')
        out.append('</li>')
        i = j
    out.append('</ol>')
    return '\n'.join(out)


def toc_link(page, current):
    here = page['file'] == current
    link = '<a href="%s"%s>%s</a>' % (page['file'], ' aria-current="page"' if here else '',
                                       entry_title(page))
    if here:
        # The headings of this page, one level below its own.
        level = min((h['level'] for h in page['headings']), default=1)
        subs = ['<li><a href="#%s">%s%s</a></li>' % (
            esc(h['id']), '<span class="secnum">%s</span> ' % h['number'] if h['number'] else '',
            h['title']) for h in page['headings'] if h['level'] == level + 1]
        if subs:
            link += '<ol class="onpage">' + ''.join(subs) + '</ol>'
    return link


def prev_next(manifest, index):
    pages = manifest['pages']
    links = []
    if index > 0:
        p = pages[index - 1]
        links.append('<a rel="prev" href="%s">← %s</a>' % (p['file'], entry_title(p)))
    else:
        links.append('<span></span>')
    if index + 1 < len(pages):
        p = pages[index + 1]
        links.append('<a rel="next" href="%s">%s →</a>' % (p['file'], entry_title(p)))
    return '<nav class="prevnext" aria-label="Previous and next">%s</nav>' % ''.join(links)


def page_title(page, book):
    text = ' '.join(x for x in (page['number'], page['text']) if x)
    return '%s · %s' % (text, book) if text else book


def write_pages(manifest, pages, out):
    template = read(os.path.join(WEB, 'page.html'))
    book = manifest['title']
    for index, page in enumerate(manifest['pages']):
        body = pages[page['file']]
        if page['kind'] == 'front':
            body = body.replace('<!--lrt-contents-->',
                                '<section class="contents"><h2>Contents</h2>%s</section>'
                                % contents(manifest))
        math = ('<script src="mathjax/MathJax.js?config=TeX-AMS_CHTML" defer></script>'
                if 'class="math ' in body else '')
        values = {'title': esc(page_title(page, book)), 'book': esc(book), 'mathjax': math,
                  'kind': page['kind'], 'contents': contents(manifest, page['file']),
                  'prevnext': prev_next(manifest, index), 'body': body}
        text = re.sub(r'\$(\w+)\$', lambda m: values[m.group(1)], template)
        write(os.path.join(out, page['file']), text)


def search_index(manifest, where, out):
    entries = []
    for e in manifest['search']:
        page = where.get(e['id'])
        if page is None:
            fail('the search index points at %r, which no page has' % e['id'])
        entries.append({'k': e['k'], 't': e['t'], 'n': e['n'],
                        'u': '%s#%s' % (page, urllib.parse.quote(e['id'], safe=':.-_'))})
    text = json.dumps(entries, ensure_ascii=False, separators=(',', ':'))
    write(os.path.join(out, 'search-index.js'),
          '// What the search box finds: sections, fragments, identifiers.\n'
          'window.LRT_SEARCH = %s;\n' % text.replace('</', '<\\/'))
    return len(entries)


def assets(out, with_math):
    for name in os.listdir(WEB):
        if name != 'page.html':
            shutil.copyfile(os.path.join(WEB, name), os.path.join(out, name))
    if not with_math:
        return
    for part in MATHJAX_PARTS:
        source = os.path.join(MATHJAX, part)
        target = os.path.join(out, 'mathjax', part)
        if os.path.isdir(source):
            shutil.copytree(source, target)
        elif os.path.isfile(source):
            os.makedirs(os.path.dirname(target), exist_ok=True)
            shutil.copyfile(source, target)
        else:
            fail('%s is missing (Debian package libjs-mathjax; run make deps)' % source)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--out', required=True)
    parser.add_argument('--cache')
    parser.add_argument('inputs', nargs='+')
    args = parser.parse_args()
    out = os.path.abspath(args.out)
    cache = os.path.abspath(args.cache or out + '-cache')

    manifest, pages = split(run_pandoc(args.inputs))
    where = link_targets(pages)
    relink(pages, where)

    # The site is written beside the old one and then takes its place, so
    # that no page of an earlier build stays behind.
    new = out + '.new'
    shutil.rmtree(new, ignore_errors=True)
    os.makedirs(new)
    compiled = figures(manifest, cache, new)
    images(pages, new)
    entries = search_index(manifest, where, new)
    write_pages(manifest, pages, new)
    assets(new, any('class="math ' in text for text in pages.values()))
    shutil.rmtree(out, ignore_errors=True)
    os.replace(new, out)
    print('html: %d pages, %d figures (%d compiled), %d search entries in %s' % (
        len(pages), len(manifest['figures']), compiled, entries, os.path.relpath(out)))


if __name__ == '__main__':
    main()
