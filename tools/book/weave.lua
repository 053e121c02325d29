--[[
weave.lua: the pandoc filter that turns lrt's chapters into a literate book,
typeset with LaTeX. What the book's fragments are, how they are numbered,
used and continued, is read by tools/book/fragments.lua; what the indexes and
each fragment's footer list, by tools/book/indexes.lua; tools/book/edition.lua
walks the document as the web edition (tools/book/html.lua) does, and this
filter typesets what it meets in LaTeX.

Each chunk gets a `<Name> =` or `<Name> +=` header with its number,
highlighted C++, fragment uses shown as `<Name 2.3>` and linked to their
definition, and a footer that says where the fragment is used, which pieces
of it come just before and after, and what it defines, with page numbers.
The environment \begin{fragment} of tools/book/preamble.tex keeps the header with
the first lines of code and the footer with the last, and leaves a record of
where they landed that tools/book/layout_check.py reads. At the end of the book
come the References (when the book has a bibliography), an Index of Fragments
and an Index of Identifiers (from noweb's `@ %def` lines).

It also resolves cross-references written as @sec:id, @fig:id, @eq:id,
@tbl:id and to exercises (@ex-6.5, @ex:name; tools/book/exercises.lua numbers
them), alone or several in one citation (as tools/book/edition.lua sets
them), and numbered equations written as `$$ ... $$ {#eq:id}`; a reference
to a label that does not exist stops the build (no "??" in the book). Other
citations (@knuth1984) are left to pandoc's citeproc, which runs after it.

Prose may show a real fragment as an example, in inline code with a class:
`Name`{.fragment-header} (a header line, alone in its paragraph),
`Name`{.fragment-use} (a use, as code shows it) and `Name`{.fragment-number}.
They name the fragment's first piece; a name that no chunk defines stops the
build, so the examples cannot go stale.

Code is highlighted here, through pandoc.write, so that fragment uses can be
turned into links inside the highlighted text. No code block reaches the LaTeX
writer, so the highlighting macros come from tools/weave.sh.
]]

package.path = pandoc.path.directory(PANDOC_SCRIPT_FILE) .. '/?.lua;' .. package.path
local fragments = require('fragments')
local edition = require('edition')
local indexes = require('indexes')
local latex_escape = require('latex_text').escape

local book   -- what tools/book/fragments.lua read

local function fail(message)
  io.stderr:write('weave.lua: ' .. message .. '\n')
  os.exit(1)
end

-- pandoc writes a code caret as \^{}, the circumflex accent over nothing,
-- a small hat at the height of capitals; \lrtcaret (tools/book/preamble.tex) is
-- the ASCII character, set larger and lower as code fonts draw it.
local function code_carets(latex)
  return (latex:gsub('\\%^{}', '\\lrtcaret{}'))
end

local function split_on(text, separator)
  local pieces, start = {}, 1
  while true do
    local i, j = text:find(separator, start, true)
    if not i then break end
    pieces[#pieces + 1] = text:sub(start, i - 1)
    start = j + 1
  end
  pieces[#pieces + 1] = text:sub(start)
  return pieces
end

-------------------------------------------------------------------------------
-- Typesetting a chunk

local function ref(chunk)
  return '\\chunkref{' .. chunk.label .. '}{' .. chunk.number .. '}'
end

local function file_name(file)
  return '\\texttt{' .. latex_escape(file) .. '}'
end

-- Page references to chunks, and a fragment's file or users, for footers and indexes.
local ref_list, destination = indexes.lister(ref, file_name)

-- Highlighted code as LaTeX, and its number of lines.
local function highlight(lines)
  local latex = code_carets(fragments.highlight(lines, 'latex', function(name)
    return '\\fraguse{' .. book.ids[name] .. '}'
  end))
  local body = latex:match('\\begin{Highlighting}%[%]\n(.-)\n\\end{Highlighting}')
  local count, blank = 0, {}
  for line in ((body or '') .. '\n'):gmatch('([^\n]*)\n') do
    count = count + 1
    if line:match('^%s*$') then blank[#blank + 1] = tostring(count) end
  end
  return latex, count, table.concat(blank, ',')
end

local function footer(chunk)
  local notes, about = {}, indexes.notes(book, chunk)
  notes[#notes + 1] = '\\fragnote{' .. (about.file and 'File' or 'Used in') .. '}{' ..
                      destination(about) .. '}'
  if about.continues then
    notes[#notes + 1] = '\\fragnote{Continues}{' .. ref(about.continues) .. '}'
  end
  if about.continued_in then
    notes[#notes + 1] = '\\fragnote{Continued in}{' .. ref(about.continued_in) .. '}'
  end
  if #about.defines > 0 then
    local ids = {}
    for _, id in ipairs(about.defines) do
      ids[#ids + 1] = '\\identdef{' .. latex_escape(id) .. '}'
    end
    notes[#notes + 1] = '\\fragnote{Defines}{' .. table.concat(ids, ', ') .. '}'
  end
  return '\\fragfooter{' .. table.concat(notes, '\\fragsep ') .. '}'
end

local function render_chunk(chunk)
  local code, lines, blank = highlight(fragments.shown_lines(chunk))
  local kind = chunk == book:first(chunk) and 'def' or 'cont'
  return pandoc.RawBlock('latex', table.concat({
    string.format('\\begin{fragment}{%s}{%d}{%s}\\fragheader{%s}{%s}{%s}{%s}', chunk.label,
                  lines, blank, chunk.label, chunk.number, book.ids[chunk.name], kind),
    code,
    footer(chunk) .. '\\end{fragment}'}, '\n'))
end

local function render_plain_code(code)
  return pandoc.RawBlock('latex', code_carets(pandoc.write(pandoc.Pandoc({code}), 'latex')))
end

-- A fragment shown as an example in the prose (see the comment at the top),
-- given its first chunk.
local function sample_number(first)
  return pandoc.RawInline('latex', '\\hyperref[' .. first.label .. ']{' .. first.number .. '}')
end

local function sample_use(first)
  return pandoc.RawInline('latex', '\\fraguse{' .. book.ids[first.name] .. '}')
end

local function sample_header(first)
  return pandoc.RawInline('latex', '\\fragheaderline{' .. book.ids[first.name] .. '}{' ..
                          first.label .. '}{' .. first.number .. '}{def}')
end

-------------------------------------------------------------------------------
-- Figures: a short caption for the List of Figures

-- Words after which a full stop does not end a sentence.
local ABBREVIATIONS = {['e.g'] = true, ['i.e'] = true, cf = true, Fig = true, Eq = true,
                       vs = true, al = true, etc = true, approx = true}

-- The caption's first sentence: up to the first full stop outside braces and
-- mathematics that is followed by a space and a capital, a command or a
-- parenthesis, after a word that is neither an abbreviation nor an initial.
local function first_sentence(latex)
  local depth, math, i = 0, false, 1
  while i <= #latex do
    local c = latex:sub(i, i)
    if c == '\\' then
      local two = latex:sub(i, i + 1)
      if two == '\\(' or two == '\\[' then math = true
      elseif two == '\\)' or two == '\\]' then math = false end
      i = i + 2
    else
      if c == '{' then depth = depth + 1
      elseif c == '}' then depth = depth - 1
      elseif c == '$' then math = not math
      elseif c == '.' and depth == 0 and not math
             and latex:sub(i + 1, i + 2):match('^%s[%u\\(]') then
        local word = latex:sub(1, i - 1):match('([%w%.]*)$')
        if not ABBREVIATIONS[word] and not word:match('^%u$') then
          return latex:sub(1, i)
        end
      end
      i = i + 1
    end
  end
  return latex
end

-- \caption{long} as \caption[first sentence]{long}, in a figure's LaTeX.
local function short_caption(latex)
  local start, open = latex:find('\\caption{', 1, true)
  if not start then return latex end
  local group = latex:match('^%b{}', open)
  if not group then return latex end
  local long = group:sub(2, -2)
  local short = first_sentence(long)
  if short == long then return latex end
  return latex:sub(1, start - 1) .. '\\caption[{' .. short .. '}]' ..
         latex:sub(open)
end

-------------------------------------------------------------------------------
-- The indexes

local function fragment_index()
  local out = {'\\begin{fragmentindex}'}
  for _, entry in ipairs(indexes.fragments(book)) do
    out[#out + 1] = '\\fragindexentry{' .. book.ids[entry.name] .. '}{' ..
                    ref_list(entry.chunks) .. '}{' .. (entry.file and 'file ' or 'used in ') ..
                    destination(entry) .. '}'
  end
  out[#out + 1] = '\\end{fragmentindex}'
  return table.concat(out, '\n')
end

local function identifier_index()
  local out = {'\\begin{identifierindex}'}
  for _, entry in ipairs(indexes.identifiers(book)) do
    out[#out + 1] = '\\identindexentry{' .. latex_escape(entry.id) .. '}{' ..
                    ref_list(entry.chunks) .. '}{' ..
                    (#entry.used_in > 0 and ('used in ' .. ref_list(entry.used_in)) or '') .. '}'
  end
  out[#out + 1] = '\\end{identifierindex}'
  return table.concat(out, '\n')
end

local function fragment_names()
  local out = {}
  for name, id in pairs(book.ids) do
    local first = book.by_name[name][1]
    out[#out + 1] = '\\fragname{' .. id .. '}{' .. latex_escape(name) .. '}{' ..
                    first.label .. '}{' .. first.number .. '}'
  end
  table.sort(out)
  return table.concat(out, '\n')
end

-------------------------------------------------------------------------------
-- Cross-references and equations

-- A cross-reference's number and link (tools/book/edition.lua sets the words
-- around them). The numbers of sections, figures, tables and equations are
-- LaTeX's; a reference to a fourth-level heading names the numbered section
-- around it (LaTeX numbers sections to the third level only,
-- tools/book/preamble.tex). Exercises are numbered by tools/book/exercises.lua.
local function reference_number(item)
  if item.kind == 'ex' then return {pandoc.Str(item.target.number)} end
  local ref = '\\ref*{' .. item.id .. '}'
  if item.kind == 'eq' then ref = '(' .. ref .. ')' end
  return {pandoc.RawInline('latex', ref)}
end

local function reference_link(item, inlines)
  local head = '\\hyperref[' .. item.id .. ']{'
  if item.kind == 'fig' or item.kind == 'tbl' then
    head = '\\floatcite{' .. item.id .. '}' .. head   -- where a float is first cited
  end
  local out = pandoc.List({pandoc.RawInline('latex', head)})
  out:extend(inlines)
  out:insert(pandoc.RawInline('latex', '}'))
  return out
end

local function number_equation(math, label)
  return pandoc.RawInline('latex', '\\begin{equation}' .. math.text ..
                          '\\label{' .. label .. '}\\end{equation}')
end

-- `<<` in T1-encoded text is a guillemet ligature: break it up.
local function break_guillemets(s)
  if not s.text:find('@<<', 1, true) then return nil end
  local parts = {}
  for i, piece in ipairs(split_on(s.text, '@<<')) do
    if i > 1 then parts[#parts + 1] = pandoc.RawInline('latex', '<{}<') end
    if piece ~= '' then parts[#parts + 1] = pandoc.Str(piece) end
  end
  return parts
end

local function inline_code(c)
  if c.text:find('^', 1, true) then
    return pandoc.RawInline('latex', code_carets(
      pandoc.write(pandoc.Pandoc({pandoc.Plain({c})}), 'latex')))
  end
  return c
end

local function figure(para)
  return pandoc.RawBlock('latex', short_caption(pandoc.write(pandoc.Pandoc({para}), 'latex')))
end

local function sample_paragraph(text)
  if text:match('^\\fragheaderline') then
    return pandoc.RawBlock('latex', '\\fragheadersample{' .. text .. '}')
  end
end

local function figure_caption(raw)
  if raw.format == 'latex' and raw.text:find('\\begin{figure}', 1, true) then
    raw.text = short_caption(raw.text)
    return raw
  end
end

-------------------------------------------------------------------------------

function Pandoc(doc)
  book = edition.read(doc, fail)
  doc = edition.typeset(doc, book, {
    equation = number_equation, number = reference_number, link = reference_link,
    sample_number = sample_number,
    sample_use = sample_use, sample_header = sample_header, inline_code = inline_code,
    chunk = render_chunk, plain_code = render_plain_code, figure = figure,
    sample_paragraph = sample_paragraph, Str = break_guillemets, RawBlock = figure_caption,
  }, fail)

  -- LaTeX numbers the chapters after \appendix A, B, ...: put it before the
  -- first appendix (a level-1 header of class appendix).
  for i, block in ipairs(doc.blocks) do
    if block.t == 'Header' and block.level == 1 and block.classes:includes('appendix') then
      doc.blocks:insert(i, pandoc.RawBlock('latex', '\\appendix'))
      break
    end
  end
  table.insert(doc.blocks, 1, pandoc.RawBlock('latex', fragment_names()))
  doc.blocks:insert(pandoc.RawBlock('latex', '\\backmatter'))
  if doc.meta.bibliography then
    -- pandoc's citeproc, run after this filter, fills the div with id refs.
    doc.blocks:insert(pandoc.Header(1, 'References', pandoc.Attr('references',
                                                                 {'unnumbered'})))
    doc.blocks:insert(pandoc.RawBlock('latex', '\\markboth{References}{References}'))
    doc.blocks:insert(pandoc.Div({}, pandoc.Attr('refs')))
  end
  doc.blocks:insert(pandoc.RawBlock('latex', fragment_index()))
  doc.blocks:insert(pandoc.RawBlock('latex', identifier_index()))
  return doc
end
