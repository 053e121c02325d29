--[[
fragments.lua: what the weave knows about a literate book, apart from how it
is typeset. tools/book/weave.lua (LaTeX) requires it; a web edition can require
it as well and typeset the same facts as HTML.

  local book = require('fragments').read(doc, fail)

takes the book's noweb chunks from tools/noweb/chunks.py (the one reading of
the chunk grammar, which the lint and the exercise tools share), finds each
in the ```cpp code block that holds it, numbers the chunks per chapter (2.7 is
chapter 2's seventh), and records:

  book.chunks        in book order: {name, number, label, chapter, lines, defs}
  book.by_name       name -> the chunks that define it, in order
  book.uses_of       name -> the chunks whose code uses it
  book.identifiers   identifier -> the chunks whose `@ %def` defines it
  book.labels        label -> {kind = 'Section' | 'Figure' | ..., level, chapter,
                     number = what a reference to it shows (see edition.read)};
                     exercises' ids too (numbered by tools/book/exercises.lua)
  book.missing       labels that cross-references name and the book lacks (see reference)

with functions over them (neighbours, shown_lines, identifier_uses, ...), and
what both editions do alike: highlighting code with its fragment uses, finding
numbered equations, figures, examples of fragments and cross-references.
It checks that reading against pandoc's code blocks and against noweb's
markup: if they disagree, the book would show code that is not the code that
is compiled.
]]

local M = {}

-- tools/noweb/chunks.py, beside this file's folder.
local CHUNKS_PY = (debug.getinfo(1, 'S').source:match('^@(.*)[/\\]') or '.')
                  .. '/../noweb/chunks.py'
-- What chunks.py read: the header line of each chunk (is_chunk_block asks
-- it), and each line of code that is a fragment use -> {indent, name}.
local headers, use_lines = {}, {}
-- Lua patterns have no alternation (a|b): shown_lines() checks the two words.
local EXERCISE_MARKER = '^%s*// (%u+) (%u+)%s*$'

function M.unescape_noweb(s)
  return (s:gsub('@<<', '<<'))
end

function M.split_lines(text)
  local lines = {}
  for line in (text .. '\n'):gmatch('(.-)\n') do lines[#lines + 1] = line end
  return lines
end

-- A code block that holds a chunk: its first line is a chunk's header as
-- chunks.py read it (so this answers after read()).
function M.is_chunk_block(block)
  return block.t == 'CodeBlock' and headers[block.text:match('^[^\n]*')] ~= nil
end

-- The indent and the name of the fragment that a line of code uses, or nil
-- where the line is not a use.
function M.use_in(line)
  local use = use_lines[line]
  if use then return use.indent, use.name end
end

function M.sorted_keys(t)
  local keys = {}
  for k in pairs(t) do keys[#keys + 1] = k end
  table.sort(keys, function(a, b)
    local la, lb = a:lower(), b:lower()
    if la == lb then return a < b end
    return la < lb
  end)
  return keys
end

-------------------------------------------------------------------------------
-- Reading the chunks

-- The chunks of the input files, as tools/noweb/chunks.py reads them:
-- {name, file, line, text, lines, ended_by, defs, uses = {{line, name}}}.
local function read_chunks(files, fail)
  local args = {CHUNKS_PY, '--lua'}
  for _, file in ipairs(files) do args[#args + 1] = file end
  local ok, out = pcall(pandoc.pipe, 'python3', args, '')
  if not ok then fail('tools/noweb/chunks.py failed: ' .. tostring(out)) end
  local index, err = load(out, 'chunks.py', 't', {})
  if not index then fail('cannot load what tools/noweb/chunks.py wrote: ' .. err) end
  local chunks = index().chunks
  headers, use_lines = {}, {}
  for _, chunk in ipairs(chunks) do
    headers[chunk.text:match('^[^\n]*')] = true
    for _, use in ipairs(chunk.uses) do
      local line = chunk.lines[use.line - chunk.line]
      use_lines[line] = {indent = line:match('^%s*'), name = use.name}
    end
  end
  return chunks
end

-- The chunk that chunks.py read for the next code block that holds one.
local function take_chunk(block, chunks, count, fail)
  local read = chunks[count]
  local where = read and (read.file .. ':' .. read.line) or 'the end of the book'
  if not read or read.text ~= block.text then
    fail(string.format('chunk %d: noweb reads <<%s>> at %s (tools/noweb/chunks.py) but '
      .. 'the weave reads the code block\n%s\nis a chunk outside a ```cpp fence, in a '
      .. 'list, or in a quote?', count, read and read.name or 'nothing', where, block.text))
  end
  if read.ended_by ~= '@' then
    fail(where .. ': chunk <<' .. read.name .. '>> does not end with @ (run make lint)')
  end
  return {name = read.name, lines = read.lines, defs = read.defs, uses = read.uses}
end

local function label_kind(label)
  if label:match('^fig:') then return 'Figure' end
  if label:match('^tbl:') then return 'Table' end
  if label:match('^eq:') then return 'Equation' end
  return 'Section'
end

-- Reads noweb's markup output into a list of {name, lines} chunks.
local function noweb_chunks(files, fail)
  local ok, out = pcall(pandoc.pipe, '/usr/lib/noweb/markup', files, '')
  if not ok then fail('noweb markup failed: ' .. tostring(out)) end
  local result, current, line = {}, nil, ''
  for record in out:gmatch('[^\n]+') do
    local kind, rest = record:match('^@(%S+) ?(.*)$')
    if kind == 'begin' and rest:match('^code') then
      current, line = {name = nil, lines = {}}, ''
    elseif current and kind == 'defn' then
      current.name = rest
    elseif current and kind == 'text' then
      line = line .. rest
    elseif current and kind == 'use' then
      line = line .. '<<' .. rest .. '>>'
    elseif current and kind == 'nl' then
      if current.seen_header then table.insert(current.lines, line) end
      current.seen_header, line = true, ''
    elseif current and kind == 'end' then
      if line ~= '' then table.insert(current.lines, line) end
      result[#result + 1] = current
      current = nil
    end
  end
  return result
end

local Book = {}
Book.__index = Book

-- Walks the document once (in document order, into divs too), numbering
-- chunks by chapter and collecting the labels that references may target.
function M.read(doc, fail)
  local read = read_chunks(PANDOC_STATE.input_files, fail)
  local book = setmetatable({chunks = {}, by_name = {}, uses_of = {}, ids = {},
                             identifiers = {}, labels = {}, missing = {}, fail = fail},
                            Book)
  -- Chapters are numbered 1, 2, ...; appendices (level-1 headers of class
  -- appendix, which must come last) A, B, ..., as LaTeX numbers them.
  local chapter, count, appendices = 0, 0, 0
  doc:walk({
    Header = function(block)
      local appendix = block.level == 1 and block.classes:includes('appendix')
      if appendix then
        appendices, count = appendices + 1, 0
        chapter = string.char(string.byte('A') + appendices - 1)
      elseif block.level == 1 and not block.classes:includes('unnumbered') then
        if appendices > 0 then
          fail('chapter "' .. pandoc.utils.stringify(block) ..
               '" stands after an appendix')
        end
        chapter, count = chapter + 1, 0
      end
      if block.identifier ~= '' then
        book.labels[block.identifier] = {
          kind = appendix and 'Appendix' or block.level == 1 and 'Chapter'
                 or 'Section',
          level = block.level, chapter = chapter}
      end
    end,
    CodeBlock = function(block)
      if not M.is_chunk_block(block) then return end
      local chunk = take_chunk(block, read, #book.chunks + 1, fail)
      if chapter == 0 then
        fail('chunk <<' .. chunk.name .. '>> stands before the first chapter')
      end
      count = count + 1
      chunk.chapter = chapter
      chunk.number = chapter .. '.' .. count
      chunk.label = 'chunk:' .. chunk.number
      book.chunks[#book.chunks + 1] = chunk
      if not book.by_name[chunk.name] then
        book.by_name[chunk.name] = {}
        book.ids[chunk.name] = 'f' .. #book.chunks
      end
      table.insert(book.by_name[chunk.name], chunk)
      for _, id in ipairs(chunk.defs) do
        book.identifiers[id] = book.identifiers[id] or {}
        table.insert(book.identifiers[id], chunk)
      end
    end,
    RawBlock = function(block)
      if block.format ~= 'latex' then return end
      for label in block.text:gmatch('\\label{([^}]+)}') do
        book.labels[label] = {kind = label_kind(label), chapter = chapter}
      end
    end,
    Image = function(img)
      if img.identifier ~= '' then
        book.labels[img.identifier] = {kind = 'Figure', chapter = chapter}
      end
    end,
    Str = function(s)
      local label = s.text:match('^{#(eq:[%w_:%-]+)}$')
      if label then book.labels[label] = {kind = 'Equation', chapter = chapter} end
    end,
  })
  local exercises = doc.meta['lrt-exercises']
  for id, number in pairs(exercises or {}) do
    book.labels[id] = {kind = 'Exercise', number = pandoc.utils.stringify(number)}
  end
  if #read > #book.chunks then
    local missed = read[#book.chunks + 1]
    fail(string.format('chunk %d: noweb reads <<%s>> at %s:%d (tools/noweb/chunks.py) but '
      .. 'the weave finds no code block that holds it; is a chunk outside a ```cpp fence, '
      .. 'in a list, or in a quote?', #book.chunks + 1, missed.name, missed.file, missed.line))
  end
  for _, chunk in ipairs(book.chunks) do
    for _, use in ipairs(chunk.uses) do
      local used = use.name
      if not book.by_name[used] then
        fail('chunk <<' .. chunk.name .. '>> ' .. chunk.number ..
             ' uses undefined fragment <<' .. used .. '>>')
      end
      book.uses_of[used] = book.uses_of[used] or {}
      table.insert(book.uses_of[used], chunk)
    end
  end
  return book
end

function Book:cross_check(files)
  local theirs = noweb_chunks(files, self.fail)
  local chunks = self.chunks
  for i = 1, math.max(#theirs, #chunks) do
    local mine, other = chunks[i], theirs[i]
    local where = mine and (' (fragment ' .. mine.number .. ')') or ''
    if not mine or not other or mine.name ~= other.name then
      self.fail(string.format('chunk %d%s: noweb reads <<%s>> but the weave reads '
        .. '<<%s>>; is a chunk outside a ```cpp fence, in a list, or in a quote?', i,
        where, other and other.name or 'nothing', mine and mine.name or 'nothing'))
    end
    local my_text = M.unescape_noweb(table.concat(mine.lines, '\n'))
    local their_text = table.concat(other.lines, '\n')
    if my_text ~= their_text then
      self.fail('chunk <<' .. mine.name .. '>> ' .. mine.number .. ': noweb and the '
           .. 'weave read different code:\n--- noweb\n' .. their_text .. '\n--- weave\n'
           .. my_text)
    end
  end
end

-------------------------------------------------------------------------------
-- Questions about the chunks

function Book:is_root(name)
  return not self.uses_of[name]
end

-- The first piece of the fragment that chunk belongs to.
function Book:first(chunk)
  return self.by_name[chunk.name][1]
end

-- The pieces of the same fragment just before and just after chunk (nil at
-- either end): a footer names these neighbours, not the whole chain.
function Book:neighbours(chunk)
  local defs = self.by_name[chunk.name]
  for i, other in ipairs(defs) do
    if other == chunk then return defs[i - 1], defs[i + 1] end
  end
end

-- The fragment named name, for a sample in the prose: fails on a name that
-- no chunk defines, so that a sample cannot go stale.
function Book:fragment(name, where)
  local defs = self.by_name[name]
  if not defs then
    self.fail(where .. ' names fragment <<' .. name .. '>>, which no chunk defines')
  end
  return defs[1]
end

-- The code with exercise markers removed (the solution book shows solutions).
function M.shown_lines(chunk)
  local out, in_stub = {}, false
  for _, line in ipairs(chunk.lines) do
    local edge, what = line:match(EXERCISE_MARKER)
    if (edge == 'BEGIN' or edge == 'END') and (what == 'SOLUTION' or what == 'STUB') then
      in_stub = (what == 'STUB' and edge == 'BEGIN')
    elseif not in_stub then
      out[#out + 1] = line
    end
  end
  return out
end

-- Highlighted code in a pandoc output format ('latex', 'html5'), with each
-- fragment use replaced by use(name, indent): the uses are set aside as
-- placeholders, so that the highlighter sees plain C++, and put back into the
-- highlighted text. Other lines are shown with noweb's escapes undone.
function M.highlight(lines, format, use)
  local placeholders, code = {}, {}
  for i, line in ipairs(lines) do
    local indent, used = M.use_in(line)
    if used then
      placeholders[#placeholders + 1] = used
      code[i] = indent .. 'LRTFRAGMENTUSE' .. #placeholders .. 'X'
    else
      code[i] = M.unescape_noweb(line)
    end
  end
  local block = pandoc.CodeBlock(table.concat(code, '\n'), {class = 'cpp'})
  local text = pandoc.write(pandoc.Pandoc({block}), format)
  return (text:gsub('LRTFRAGMENTUSE(%d+)X', function(i)
    return use(placeholders[tonumber(i)])
  end))
end

-- A fragment shown as an example in the prose, `Name`{.fragment-use} and
-- the like: the class, or nil for other inline code.
local SAMPLE = {['fragment-header'] = true, ['fragment-use'] = true,
                ['fragment-number'] = true}

function M.sample_class(code)
  for _, class in ipairs(code.classes) do
    if SAMPLE[class] then return class end
  end
end

-- A figure written in Markdown: an image alone in its paragraph, with a
-- caption (pandoc gives it the title "fig:").
function M.is_figure(block)
  return block.t == 'Para' and #block.content == 1 and block.content[1].t == 'Image'
         and block.content[1].title:match('^fig:') ~= nil
end

-- A numbered equation is written `$$ x $$ {#eq:id}`, which arrives as Math
-- followed by Str "{#eq:id}". Returns the inlines with each such pair
-- replaced by render(math, label).
function M.number_equations(inlines, render)
  local out, i = {}, 1
  while i <= #inlines do
    local el = inlines[i]
    local label, j
    if el.t == 'Math' and el.mathtype == 'DisplayMath' then
      j = i + 1
      while inlines[j] and (inlines[j].t == 'Space' or inlines[j].t == 'SoftBreak') do
        j = j + 1
      end
      label = inlines[j] and inlines[j].t == 'Str' and
              inlines[j].text:match('^{#(eq:[%w_:%-]+)}$')
    end
    if label then
      out[#out + 1] = render(el, label)
      i = j + 1
    else
      out[#out + 1] = el
      i = i + 1
    end
  end
  return out
end

-- The targets of a cross-reference, @sec:id, @fig:id, @eq:id, @tbl:id or an
-- exercise's @ex-6.5 or @ex:name, or of several in one citation,
-- [@eq:a; @eq:b]: a list of {id, kind = 'sec' | 'fig' | 'eq' | 'tbl' | 'ex',
-- target = the label's record}, in the order written, and whether the
-- citation asks for the numbers alone ([-@eq:a], "(3.5)" rather than
-- "Equation (3.5)"). nil for other citations, which are citeproc's; a label
-- that does not exist is added to book.missing (and nil returned).
local function reference_kind(id)
  if id:match('^ex[:%-]') then return 'ex' end
  local kind = id:match('^(%a+):')
  if kind == 'sec' or kind == 'fig' or kind == 'eq' or kind == 'tbl' then return kind end
end

function Book:references(cite)
  local items, others, missing = {}, {}, false
  for _, citation in ipairs(cite.citations) do
    local kind = reference_kind(citation.id)
    if not kind then
      others[#others + 1] = citation.id
    else
      local target = self.labels[citation.id]
      if not target then
        self.missing[#self.missing + 1] = citation.id
        missing = true
      end
      items[#items + 1] = {id = citation.id, kind = kind, target = target}
    end
  end
  if #items == 0 then return nil end
  if #others > 0 then
    self.fail('the citation ' .. pandoc.utils.stringify(cite) .. ' mixes cross-references ' ..
              'with references to the bibliography (' .. table.concat(others, ', ') ..
              '): write them apart')
  end
  if missing then return nil end
  return items, cite.citations[1].mode == 'SuppressAuthor'
end

-- Chunks whose code mentions an identifier as a whole word, other than where
-- it is defined (operators and other non-words are listed without uses).
-- (A whole word is a longest run of letters, digits and _: each chunk's set of
-- them is made once, since the index asks about every identifier.)
function Book:identifier_uses(id)
  if not id:match('^[%a_][%w_]*$') then return {} end
  if not self.words then
    self.words = {}
    for _, chunk in ipairs(self.chunks) do
      local words = {}
      for _, line in ipairs(chunk.lines) do
        if not M.use_in(line) then
          for word in line:gmatch('[%w_]+') do words[word] = true end
        end
      end
      self.words[chunk] = words
    end
  end
  local result, skip = {}, {}
  for _, chunk in ipairs(self.identifiers[id]) do skip[chunk] = true end
  for _, chunk in ipairs(self.chunks) do
    if not skip[chunk] and self.words[chunk][id] then result[#result + 1] = chunk end
  end
  return result
end

return M
