--[[
html.lua: the pandoc filter that turns lrt's chapters into the web edition.
What the book's fragments are, how they are numbered, used and continued, is
read by tools/book/fragments.lua, as for the PDF (tools/book/weave.lua); this
filter typesets the same facts as HTML, and tools/book/html_site.py makes
pages of it. The document is walked as the PDF's is (tools/book/edition.lua);
what is set here lives in files of one job each:

  html_numbers.lua    the numbers of headings, figures, tables, equations
  html_fragments.lua  chunks, fragment samples, plain code and the indexes
  html_figures.lua    figures and tables, and raw LaTeX in general
  html_pages.lua      the pages, the title block and the search entries
  html_text.lua       escapes, inlines as HTML or text, the manifest's JSON

Its output is one HTML body, as pandoc writes it with --mathjax and
--citeproc, in which:

  - the first block is <script type="application/json" id="lrt-manifest">:
    the pages (file, title, number, the headings on each), the entries of the
    search (sections, fragments, identifiers, each with the id it points at)
    and the TikZ figures to compile (name and LaTeX);
  - <!--lrt-page FILE--> starts each page, <!--lrt-contents--> marks where
    the front page lists the contents;
  - every link inside the book is written "#id"; the site writer points it at
    the page that holds id.

Headings, figures, tables and equations carry the numbers of the PDF;
fragments have its headers, numbers, uses and footers, and an anchor each
(#chunk:2.7); the Index of Fragments and the Index of Identifiers, and the
References (citeproc's), are pages at the end. Cross-references @sec:,
@fig:, @eq:, @tbl: and to exercises become links with the target's number,
set as in the PDF (tools/book/edition.lua); one to a label the book lacks
stops the build.
]]

package.path = pandoc.path.directory(PANDOC_SCRIPT_FILE) .. '/?.lua;' .. package.path
local edition = require('edition')
local fragments = require('fragments')
local html_figures = require('html_figures')
local html_fragments = require('html_fragments')
local html_numbers = require('html_numbers')
local html_pages = require('html_pages')
local html_text = require('html_text')
local indexes = require('indexes')

local raw = html_text.raw

local function fail(message)
  io.stderr:write('html.lua: ' .. message .. '\n')
  os.exit(1)
end

-- A cross-reference's number and link (tools/book/edition.lua sets the words
-- around them).
local function reference_number(item)
  local number = item.target.number
  return {pandoc.Str(item.kind == 'eq' and '(' .. number .. ')' or number)}
end

local function reference_link(item, inlines)
  return {pandoc.Link(inlines, '#' .. item.id)}
end

local function equation(numbers)
  return function(math, label)
    return pandoc.Span({pandoc.Math('DisplayMath', math.text .. ' \\tag{' ..
                                    numbers[label] .. '}')}, {id = label, class = 'equation'})
  end
end

-- The chapters at the end: the References (when the book has a
-- bibliography; citeproc fills the div with id refs) and the two indexes.
local function back_matter(doc, code, fragment_entries, identifier_entries)
  local blocks = {}
  local function chapter(title, id)
    blocks[#blocks + 1] = pandoc.Header(1, title, pandoc.Attr(id, {'unnumbered'}))
  end
  if doc.meta.bibliography then
    chapter('References', 'references')
    blocks[#blocks + 1] = pandoc.Div({}, pandoc.Attr('refs'))
  end
  chapter('Index of Fragments', 'index-of-fragments')
  blocks[#blocks + 1] = raw(code.fragment_index(fragment_entries))
  chapter('Index of Identifiers', 'index-of-identifiers')
  blocks[#blocks + 1] = raw(code.identifier_index(identifier_entries))
  return blocks
end

local function text_width(meta)
  for _, item in ipairs(meta.geometry or {}) do
    local width = pandoc.utils.stringify(item):match('^textwidth=(.+)$')
    if width then return width end
  end
  return ''
end

function Pandoc(doc)
  local book = edition.read(doc, fail)
  local code = html_fragments.new(book)
  local fragment_entries, identifier_entries = indexes.fragments(book), indexes.identifiers(book)
  local numbers
  doc, numbers = html_numbers.number_labels(doc)
  local figures = html_figures.new(numbers, fail)
  doc.blocks:extend(back_matter(doc, code, fragment_entries, identifier_entries))
  table.insert(doc.blocks, 1, html_pages.title_block(doc.meta))
  local blocks, pages = html_pages.paginate(doc.blocks, fail)
  doc.blocks = blocks

  doc = edition.typeset(doc, book, {
    equation = equation(numbers), number = reference_number, link = reference_link,
    sample_number = code.sample_number, sample_use = code.sample_use,
    sample_header = code.sample_header, sample_paragraph = code.sample_paragraph,
    inline_code = function(c) return c end, chunk = code.chunk, plain_code = code.plain_code,
    figure = figures.image_figure, RawBlock = figures.raw_latex,
    Str = function(s)
      if s.text:find('@<<', 1, true) then return pandoc.Str(fragments.unescape_noweb(s.text)) end
    end,
  }, fail)

  local manifest = {pages = pages, figures = figures.drawings,
                    search = html_pages.search_entries(pages, fragment_entries,
                                                       identifier_entries),
                    textwidth = text_width(doc.meta),
                    title = pandoc.utils.stringify(doc.meta.title or '')}
  table.insert(doc.blocks, 1, raw('<script type="application/json" id="lrt-manifest">' ..
                                  html_text.json(manifest, fail) .. '</script>'))
  return doc
end
