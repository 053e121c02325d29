--[[
html.lua: the pandoc filter that turns lrt's chapters into the web edition.
What the book's fragments are, how they are numbered, used and continued, is
read by tools/book/fragments.lua, as for the PDF (tools/book/weave.lua); this filter
typesets the same facts as HTML, and tools/book/html_site.py makes pages of it.

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

A page is a section (a second-level heading), or a whole chapter where the
chapter is short; a long section is cut at its third-level headings. Headings,
figures, tables and equations carry the numbers of the PDF: chapters,
sections to the third level (2.10.4); figures, tables and numbered equations
by chapter (Figure 2.3, Equation (2.3)). Fragments have the PDF's headers,
numbers, uses, "Used in / Continues / Continued in / Defines" lines, and an
anchor each (#chunk:2.7); the Index of Fragments and the Index of
Identifiers, and the References (citeproc's), are pages at the end.

A figure drawn with TikZ in the chapters (raw LaTeX) is compiled on its own
to SVG by the site writer; a table in raw LaTeX is read by pandoc's LaTeX
reader. Cross-references @sec:, @fig:, @eq:, @tbl: become links with the
target's number; one to a label the book lacks stops the build.
]]

package.path = pandoc.path.directory(PANDOC_SCRIPT_FILE) .. '/?.lua;' .. package.path
local fragments = require('fragments')

-- A chapter of fewer words than this is one page; a section of more words
-- than that is cut into pages at its third-level headings.
local SHORT_CHAPTER_WORDS = 2500
local LONG_SECTION_WORDS = 6000

local book      -- what tools/book/fragments.lua read
local numbers = {}   -- label -> the number a reference to it shows

local function fail(message)
  io.stderr:write('html.lua: ' .. message .. '\n')
  os.exit(1)
end

local function escape(s)
  return (s:gsub('[&<>"]', {['&'] = '&amp;', ['<'] = '&lt;', ['>'] = '&gt;',
                            ['"'] = '&quot;'}))
end

-- Inlines as HTML, for the side bar and the titles of links: pandoc sets
-- their mathematics in HTML itself, under a class that MathJax leaves alone.
local function html_of(inlines)
  return (pandoc.write(pandoc.Pandoc({pandoc.Plain(inlines)}), 'html5'):gsub('\n', ' ')
          :gsub('<span class="math inline">', '<span class="math-text">'))
end

local function text_of(inlines)
  return (pandoc.write(pandoc.Pandoc({pandoc.Plain(inlines)}), 'plain'):gsub('%s+', ' ')
          :gsub('^ ', ''):gsub(' $', ''))
end

local function raw(html)
  return pandoc.RawBlock('html', html)
end

-- JSON for the manifest: tables with [1] (or empty) are arrays. Characters
-- that could end the <script> element are written as \u escapes.
local function json(value)
  local kind = type(value)
  if kind == 'string' then
    return '"' .. value:gsub('[%c"\\<>&]', function(c)
      return string.format('\\u%04x', c:byte())
    end) .. '"'
  elseif kind == 'number' or kind == 'boolean' then
    return tostring(value)
  elseif kind == 'table' then
    local parts = {}
    if value[1] ~= nil or next(value) == nil then
      for _, item in ipairs(value) do parts[#parts + 1] = json(item) end
      return '[' .. table.concat(parts, ',') .. ']'
    end
    for _, key in ipairs(fragments.sorted_keys(value)) do
      parts[#parts + 1] = json(key) .. ':' .. json(value[key])
    end
    return '{' .. table.concat(parts, ',') .. '}'
  end
  fail('cannot write a ' .. kind .. ' as JSON')
end

-- Whether raw LaTeX only decides where a printed page ends (\newpage,
-- \clearpage, or such a choice made by \ifdim on the space left on the
-- page): a web page has no such end, so there is nothing to show.
local function page_break_only(text)
  local rest = text:gsub('\\ifdim.-\\fi', ''):gsub('\\par', '')
                   :gsub('\\newpage', ''):gsub('\\clearpage', ''):gsub('%s', '')
  return rest == ''
end

-------------------------------------------------------------------------------
-- Numbers: headings, figures, tables and equations, as LaTeX numbers them

-- An identifier's anchor: "ident-" and its characters, each one that is not
-- a letter, digit or _ written as -hex (operator[] is ident-operator-5b-5d).
local function ident_anchor(id)
  return 'ident-' .. id:gsub('[^%w_]', function(c)
    return string.format('-%02x', c:byte())
  end)
end

-- Numbers every heading (a span.secnum in front of its text), figure, table
-- and numbered equation, and records the number of each label. A
-- fourth-level heading has no number of its own; a reference to it names
-- the numbered heading before it, as in the PDF.
local function number_labels(doc)
  -- Chapters are numbered 1, 2, ...; appendices (level-1 headings of class
  -- appendix) A, B, ..., as in the PDF.
  local chapter, section, subsection, chapters, appendices = 0, 0, 0, 0, 0
  local current, counts = nil, {}
  local function count(kind, label)
    counts[kind] = (counts[kind] or 0) + 1
    numbers[label] = chapter .. '.' .. counts[kind]
  end
  return doc:walk({
    traverse = 'topdown',
    Header = function(h)
      local shown
      if h.classes:includes('unnumbered') or (chapter == 0 and h.level > 1) then
        if h.level == 1 then current = nil end
      elseif h.level == 1 then
        if h.classes:includes('appendix') then
          appendices = appendices + 1
          chapter = string.char(string.byte('A') + appendices - 1)
        else
          chapters = chapters + 1
          chapter = chapters
        end
        section, subsection, counts = 0, 0, {}
        current = tostring(chapter)
        shown = current
      elseif h.level == 2 then
        section, subsection = section + 1, 0
        current = chapter .. '.' .. section
        shown = current
      elseif h.level == 3 then
        subsection = subsection + 1
        current = chapter .. '.' .. section .. '.' .. subsection
        shown = current
      end
      if h.identifier ~= '' then numbers[h.identifier] = current end
      if shown then
        h.content:insert(1, pandoc.Span({pandoc.Str(shown)}, {class = 'secnum'}))
        h.content:insert(2, pandoc.Space())
        h.attributes.number = shown
      end
      return h, false
    end,
    RawBlock = function(block)
      if block.format ~= 'latex' then return nil end
      local kind = block.text:match('\\begin{(%a+)}')
      local label = block.text:match('\\label{([^}]+)}')
      if label and (kind == 'figure' or kind == 'table') then count(kind, label) end
    end,
    Para = function(para)
      if fragments.is_figure(para) and para.content[1].identifier ~= '' then
        count('figure', para.content[1].identifier)
      end
    end,
    Str = function(s)
      local label = s.text:match('^{#(eq:[%w_:%-]+)}$')
      if label then count('equation', label) end
    end,
  })
end

-------------------------------------------------------------------------------
-- Fragments

local function chunk_link(chunk, text, class)
  return string.format('<a%s href="#%s" title="%s">%s</a>',
    class and (' class="' .. class .. '"') or '', chunk.label,
    escape('⟨' .. chunk.name .. '⟩ ' .. chunk.number), text or chunk.number)
end

local function link_list(list)
  local seen, parts = {}, {}
  for _, chunk in ipairs(list) do
    if not seen[chunk] then
      seen[chunk] = true
      parts[#parts + 1] = chunk_link(chunk)
    end
  end
  return table.concat(parts, ', ')
end

local function use_html(name)
  local first = book.by_name[name][1]
  return chunk_link(first, '⟨<span class="fragusename">' .. escape(name) ..
                    '</span> <span class="fragnum">' .. first.number .. '</span>⟩',
                    'fraguse')
end

-- pandoc numbers the lines of a code block with anchors (cb1-1, ...) that
-- would repeat in every block written on its own: they are dropped.
local function without_line_anchors(html)
  return (html:gsub('<a href="#cb%d+%-%d+" aria%-hidden="true" tabindex="%-1"></a>', '')
              :gsub('<span id="cb%d+%-%d+">', '<span>')
              :gsub('<div class="sourceCode" id="cb%d+">', '<div class="sourceCode">'))
end

local function note(key, value)
  return '<span class="fragnote"><span class="notekey">' .. key .. ':</span> ' ..
         value .. '</span>'
end

local function footer(chunk)
  local notes = {}
  if book:is_root(chunk.name) then
    notes[#notes + 1] = note('File', '<code>tangled/' .. escape(chunk.name) .. '</code>')
  else
    notes[#notes + 1] = note('Used in', link_list(book.uses_of[chunk.name]))
  end
  local previous, next = book:neighbours(chunk)
  if previous then notes[#notes + 1] = note('Continues', chunk_link(previous)) end
  if next then notes[#notes + 1] = note('Continued in', chunk_link(next)) end
  if #chunk.defs > 0 then
    local ids = {}
    for _, id in ipairs(chunk.defs) do
      ids[#ids + 1] = '<a class="ident" href="#' .. ident_anchor(id) .. '"><code>' ..
                      escape(id) .. '</code></a>'
    end
    notes[#notes + 1] = note('Defines', table.concat(ids, ', '))
  end
  return '<div class="fragfoot">' .. table.concat(notes, ' ') .. '</div>'
end

local function header_line(chunk, number_link)
  local op = chunk == book:first(chunk) and '≡' or '+≡'
  local number = number_link and chunk_link(chunk, nil, 'fragnum') or
                 '<span class="fragnum">' .. chunk.number .. '</span>'
  return '<div class="fraghead"><a class="fragname" href="#' .. chunk.label .. '">⟨' ..
         escape(chunk.name) .. '⟩</a>&nbsp;' .. op .. ' ' .. number .. '</div>'
end

local function render_chunk(chunk)
  local code = fragments.highlight(fragments.shown_lines(chunk), 'html5', use_html)
  return raw('<div class="fragment" id="' .. chunk.label .. '">' .. header_line(chunk) ..
             without_line_anchors(code) .. footer(chunk) .. '</div>')
end

local function render_plain_code(block)
  local lines = fragments.split_lines(block.text)
  for i, line in ipairs(lines) do lines[i] = fragments.unescape_noweb(line) end
  local code = pandoc.CodeBlock(table.concat(lines, '\n'), block.attr)
  return raw(without_line_anchors(pandoc.write(pandoc.Pandoc({code}), 'html5')))
end

-- A fragment shown as an example in the prose (see tools/book/weave.lua).
local function render_sample(code)
  local class = fragments.sample_class(code)
  if not class then return nil end
  local first = book:fragment(code.text, 'the example `' .. code.text .. '`{.' .. class .. '}')
  if class == 'fragment-number' then
    return pandoc.RawInline('html', chunk_link(first))
  elseif class == 'fragment-use' then
    return pandoc.RawInline('html', use_html(first.name))
  end
  return pandoc.RawInline('html', header_line(first, true))
end

-------------------------------------------------------------------------------
-- Figures and tables

local figures = {}   -- {name, latex} of each TikZ figure, for the site writer

-- The LaTeX group that starts at text's position open ("{...}"), without
-- its braces.
local function group_at(text, open)
  local group = text:match('^%b{}', open)
  return group and group:sub(2, -2)
end

local function caption_of(latex, label)
  local _, open = latex:find('\\caption{', 1, true)
  local caption = open and group_at(latex, open)
  if not caption then fail(label .. ': a figure or table without \\caption') end
  local blocks = pandoc.read(caption, 'latex').blocks
  local inlines = pandoc.List()
  for i, block in ipairs(blocks) do
    if i > 1 then inlines:insert(pandoc.Space()) end
    inlines:extend(block.content or {})
  end
  return inlines
end

local function figure_blocks(label, kind, image, caption)
  local blocks = {raw('<figure id="' .. label .. '" class="' .. kind .. '">'), image,
                  raw('<figcaption>')}
  local inlines = pandoc.List({pandoc.Span({pandoc.Str('Figure\u{a0}' .. numbers[label] .. ':')},
                                           {class = 'figlabel'}), pandoc.Space()})
  inlines:extend(caption)
  blocks[#blocks + 1] = pandoc.Plain(inlines)
  blocks[#blocks + 1] = raw('</figcaption></figure>')
  return blocks
end

-- A figure in raw LaTeX: what stands between \begin{figure} (and \centering)
-- and \caption is drawn on its own page by the site writer, as SVG.
local function tikz_figure(latex)
  local label = latex:match('\\label{([^}]+)}')
  if not label then fail('a LaTeX figure without \\label: ' .. latex:sub(1, 200)) end
  local body = latex:match('\\begin{figure}%b[]%s*(.-)\\caption{') or
               latex:match('\\begin{figure}%s*(.-)\\caption{')
  if not body then fail(label .. ': no drawing before \\caption') end
  body = body:gsub('^\\centering%s*', '')
  local name = label:gsub('[^%w%-]', '-')
  figures[#figures + 1] = {name = name, latex = body}
  local image = raw('<img src="figures/' .. name .. '.svg" alt="Figure ' .. numbers[label] ..
                    '">')
  return figure_blocks(label, 'drawing', image, caption_of(latex, label))
end

-- A table in raw LaTeX, read by pandoc: its rows between the first two
-- \hline are its head, and its caption is numbered.
local function latex_table(latex)
  local label = latex:match('\\label{([^}]+)}')
  if not label then fail('a LaTeX table without \\label: ' .. latex:sub(1, 200)) end
  local tables = {}
  pandoc.read(latex, 'latex'):walk({Table = function(t) tables[#tables + 1] = t end})
  if #tables ~= 1 then fail(label .. ': pandoc reads ' .. #tables .. ' tables in it') end
  local tbl = tables[1]
  local rule = latex:find('\\hline', 1, true)
  local head_rows = 0
  if rule then
    local after = latex:sub(rule + 6)
    local second = after:find('\\hline', 1, true)
    if second then
      for _ in after:sub(1, second):gmatch('\\\\') do head_rows = head_rows + 1 end
    end
  end
  local body = tbl.bodies[1].body
  for _ = 1, head_rows do
    tbl.head.rows:insert(body:remove(1))
  end
  local caption = pandoc.List({pandoc.Span({pandoc.Str('Table\u{a0}' .. numbers[label] .. ':')},
                                           {class = 'figlabel'}), pandoc.Space()})
  caption:extend(caption_of(latex, label))
  tbl.caption = {long = {pandoc.Plain(caption)}}
  return pandoc.Div({tbl}, {id = label, class = 'table'})
end

local function image_figure(para)
  local img = para.content[1]
  local label = img.identifier
  if label == '' then fail('a figure without an identifier: ' .. img.src) end
  local image = pandoc.Plain({pandoc.Image({pandoc.Str('Figure ' .. numbers[label])}, img.src,
                                           '', {class = 'figure-image'})})
  return figure_blocks(label, 'image', image, img.caption)
end

-------------------------------------------------------------------------------
-- Cross-references and equations

local function crossref(cite)
  local id, kind, target = book:reference(cite)
  if not id then return nil end
  local number = numbers[id]
  if not number then fail('@' .. id .. ': a label without a number') end
  local text
  if kind == 'eq' then
    text = 'Equation\u{a0}(' .. number .. ')'
  else
    local name = kind == 'fig' and 'Figure' or kind == 'tbl' and 'Table' or target.kind
    text = name .. '\u{a0}' .. number
  end
  return pandoc.Link({pandoc.Str(text)}, '#' .. id)
end

local function number_equations(inlines)
  return fragments.number_equations(inlines, function(math, label)
    return pandoc.Span({pandoc.Math('DisplayMath', math.text .. ' \\tag{' ..
                                    numbers[label] .. '}')}, {id = label, class = 'equation'})
  end)
end

-------------------------------------------------------------------------------
-- The indexes and the title

local function fragment_index()
  local out = {'<ul class="index fragment-index">'}
  for _, name in ipairs(fragments.sorted_keys(book.by_name)) do
    local entry = '<li><span class="fragname">⟨' .. escape(name) .. '⟩</span> ' ..
                  link_list(book.by_name[name]) .. '; '
    if book:is_root(name) then
      entry = entry .. 'file <code>tangled/' .. escape(name) .. '</code>'
    else
      entry = entry .. 'used in ' .. link_list(book.uses_of[name])
    end
    out[#out + 1] = entry .. '</li>'
  end
  out[#out + 1] = '</ul>'
  return table.concat(out, '\n')
end

local function identifier_index()
  local out = {'<ul class="index identifier-index">'}
  for _, id in ipairs(fragments.sorted_keys(book.identifiers)) do
    local uses = book:identifier_uses(id)
    out[#out + 1] = '<li id="' .. ident_anchor(id) .. '"><code>' .. escape(id) ..
                    '</code> ' .. link_list(book.identifiers[id]) ..
                    (#uses > 0 and ('; used in ' .. link_list(uses)) or '') .. '</li>'
  end
  out[#out + 1] = '</ul>'
  return table.concat(out, '\n')
end

local function back_matter(doc)
  local blocks = {}
  local function chapter(title, id)
    blocks[#blocks + 1] = pandoc.Header(1, title, pandoc.Attr(id, {'unnumbered'}))
  end
  if doc.meta.bibliography then
    chapter('References', 'references')
    blocks[#blocks + 1] = pandoc.Div({}, pandoc.Attr('refs'))
  end
  chapter('Index of Fragments', 'index-of-fragments')
  blocks[#blocks + 1] = raw(fragment_index())
  chapter('Index of Identifiers', 'index-of-identifiers')
  blocks[#blocks + 1] = raw(identifier_index())
  return blocks
end

local function title_block(meta)
  local parts = {'<header class="titleblock">'}
  local function add(field, tag, class)
    if meta[field] then
      parts[#parts + 1] = '<' .. tag .. ' class="' .. class .. '">' ..
                          html_of(pandoc.utils.type(meta[field]) == 'Inlines' and meta[field]
                                  or {pandoc.Str(pandoc.utils.stringify(meta[field]))}) ..
                          '</' .. tag .. '>'
    end
  end
  add('title', 'h1', 'title')
  add('subtitle', 'p', 'subtitle')
  add('author', 'p', 'author')
  add('date', 'p', 'date')
  parts[#parts + 1] = '</header>'
  return raw(table.concat(parts, '\n'))
end

-------------------------------------------------------------------------------
-- Pages

local function words(blocks)
  local n = 0
  for _, block in ipairs(blocks) do
    for _ in pandoc.utils.stringify(block):gmatch('%S+') do n = n + 1 end
  end
  return n
end

-- The page file of a heading: the chapter's number and the heading's id
-- without "sec:" (and without the chapter's number, where the id repeats it).
local function page_file(chapter, header)
  local slug = header.identifier:gsub('^sec:', ''):gsub('^' .. chapter .. '%-', '')
  if slug == '' then fail('a heading without an identifier: ' ..
                          pandoc.utils.stringify(header)) end
  return (chapter ~= '' and (chapter .. '-') or '') .. slug:gsub('[^%w%-_.]', '-') .. '.html'
end

local function heading_entry(h)
  local inlines = pandoc.List(h.content)
  if h.attributes.number then   -- the number span and the space after it
    inlines = inlines:filter(function(_, i) return i > 2 end)
  end
  return {id = h.identifier, level = h.level, number = h.attributes.number or '',
          title = html_of(inlines), text = text_of(inlines)}
end

-- Splits the top-level blocks into pages (see the top of this file): the
-- blocks with a marker in front of each page, and the list of pages.
local function paginate(blocks)
  -- Groups: the front matter, each chapter, each back-matter chapter.
  local groups, group, chapters = {}, nil, 0
  for _, block in ipairs(blocks) do
    local numbered = block.t == 'Header' and block.attributes.number ~= nil
    if numbered then chapters = chapters + 1 end
    if block.t == 'Header' and block.level == 1 and (numbered or chapters > 0) then
      group = {header = block, blocks = {}}
      groups[#groups + 1] = group
    elseif not group then
      group = {front = true, blocks = {}}
      groups[#groups + 1] = group
    end
    table.insert(group.blocks, block)
  end

  local pages = {}
  local function cut(list, level)   -- runs of blocks, each from a heading of level
    local runs, run = {}, nil
    for _, block in ipairs(list) do
      if not run or (block.t == 'Header' and block.level == level) then
        run = {}
        runs[#runs + 1] = run
      end
      run[#run + 1] = block
    end
    return runs
  end
  local function add_page(file, kind, run, chapter)
    local head = run[1].t == 'Header' and run[1] or nil
    local page = {file = file, kind = kind, chapter = chapter, blocks = run,
                  number = head and head.attributes.number or '',
                  title = '', text = '', headings = {}}
    if head then
      local entry = heading_entry(head)
      page.title, page.text = entry.title, entry.text
    end
    for _, block in ipairs(run) do
      if block.t == 'Header' and block.identifier ~= '' then
        page.headings[#page.headings + 1] = heading_entry(block)
      end
    end
    pages[#pages + 1] = page
  end

  for _, g in ipairs(groups) do
    if g.front then
      table.insert(g.blocks, raw('<!--lrt-contents-->'))
      add_page('index.html', 'front', g.blocks, '')
    elseif not g.header.attributes.number then
      add_page(page_file('', g.header), 'back', g.blocks, '')
    else
      local number = g.header.attributes.number
      local chapter = tonumber(number) and string.format('%02d', tonumber(number)) or number
      if words(g.blocks) < SHORT_CHAPTER_WORDS then
        add_page(page_file(chapter, g.header), 'chapter', g.blocks, chapter)
      else
        for i, run in ipairs(cut(g.blocks, 2)) do
          local kind = i == 1 and 'chapter' or 'section'
          local parts = {run}
          if i > 1 and words(run) > LONG_SECTION_WORDS then parts = cut(run, 3) end
          for j, part in ipairs(parts) do
            add_page(page_file(chapter, part[1]), j == 1 and kind or 'subsection', part,
                     chapter)
          end
        end
      end
    end
  end

  local out, seen = {}, {}
  for _, page in ipairs(pages) do
    if seen[page.file] then fail('two pages would be ' .. page.file) end
    seen[page.file] = true
    out[#out + 1] = raw('<!--lrt-page ' .. page.file .. '-->')
    for _, block in ipairs(page.blocks) do out[#out + 1] = block end
    page.blocks = nil
  end
  return out, pages
end

-- What the search box finds: every numbered or labelled heading, every
-- fragment (by its name) and every identifier (at its first definition).
local function search_entries(pages)
  local entries = {}
  for _, page in ipairs(pages) do
    for _, h in ipairs(page.headings) do
      entries[#entries + 1] = {k = 's', t = h.text, n = h.number, id = h.id}
    end
  end
  for _, name in ipairs(fragments.sorted_keys(book.by_name)) do
    local first = book.by_name[name][1]
    entries[#entries + 1] = {k = 'f', t = name, n = first.number, id = first.label}
  end
  for _, id in ipairs(fragments.sorted_keys(book.identifiers)) do
    local first = book.identifiers[id][1]
    entries[#entries + 1] = {k = 'i', t = id, n = first.number, id = first.label}
  end
  return entries
end

local function text_width(meta)
  for _, item in ipairs(meta.geometry or {}) do
    local width = pandoc.utils.stringify(item):match('^textwidth=(.+)$')
    if width then return width end
  end
  return ''
end

-------------------------------------------------------------------------------

function Pandoc(doc)
  local rendered = 0
  book = fragments.read(doc, fail)
  local files = {}
  for _, file in ipairs(PANDOC_STATE.input_files) do files[#files + 1] = file end
  book:cross_check(files)

  doc = number_labels(doc)
  doc.blocks:extend(back_matter(doc))
  table.insert(doc.blocks, 1, title_block(doc.meta))
  local blocks, pages = paginate(doc.blocks)
  doc.blocks = blocks

  doc = doc:walk({
    Inlines = number_equations,
  })
  doc = doc:walk({
    Cite = crossref,
    Str = function(s)
      if s.text:find('@<<', 1, true) then return pandoc.Str(fragments.unescape_noweb(s.text)) end
    end,
    Code = function(c)
      local sample = render_sample(c)
      if sample then return sample end
      if c.text:find('@<<', 1, true) then c.text = fragments.unescape_noweb(c.text) end
      return c
    end,
    CodeBlock = function(block)
      if fragments.is_chunk_block(block) then
        rendered = rendered + 1  -- this walk meets chunks in the order read()
        return render_chunk(book.chunks[rendered])
      end
      return render_plain_code(block)
    end,
    Para = function(para)
      if fragments.is_figure(para) then return image_figure(para) end
      local only = #para.content == 1 and para.content[1]
      if only and only.t == 'RawInline' and only.text:match('^<div class="fraghead"') then
        return raw('<div class="fragment sample">' .. only.text .. '</div>')
      end
    end,
    RawBlock = function(block)
      if block.format ~= 'latex' then return nil end
      if block.text:find('\\begin{figure}', 1, true) then return tikz_figure(block.text) end
      if block.text:find('\\begin{table}', 1, true) then return latex_table(block.text) end
      if page_break_only(block.text) then return {} end
      fail('raw LaTeX that the web edition cannot show: ' .. block.text:sub(1, 200))
    end,
  })
  if #book.missing > 0 then
    fail('references to undefined labels: ' .. table.concat(book.missing, ', '))
  end
  if rendered ~= #book.chunks then
    fail('typeset ' .. rendered .. ' of ' .. #book.chunks .. ' chunks')
  end

  local manifest = {pages = pages, search = search_entries(pages), figures = figures,
                    textwidth = text_width(doc.meta),
                    title = pandoc.utils.stringify(doc.meta.title or '')}
  table.insert(doc.blocks, 1, raw('<script type="application/json" id="lrt-manifest">' ..
                                  json(manifest) .. '</script>'))
  return doc
end
