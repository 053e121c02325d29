--[[
fragments.lua: what the weave knows about a literate book, apart from how it
is typeset. tools/weave.lua (LaTeX) requires it; a web edition can require
it as well and typeset the same facts as HTML.

  local book = require('fragments').read(doc, fail)

reads every ```cpp block that starts with `<<Name>>=` as a noweb chunk,
numbers the chunks per chapter (2.7 is chapter 2's seventh), and records:

  book.chunks        in book order: {name, number, label, chapter, lines, defs}
  book.by_name       name -> the chunks that define it, in order
  book.uses_of       name -> the chunks whose code uses it
  book.identifiers   identifier -> the chunks whose `@ %def` defines it
  book.labels        label -> {kind = 'Section' | 'Figure' | ..., level, chapter}

with functions over them (neighbours, shown_lines, identifier_uses, ...).
It checks its own reading of the chunks against noweb's markup: if the two
disagree, the book would show code that is not the code that is compiled.
]]

local M = {}

M.CHUNK_HEADER = '^<<(.+)>>=%s*$'
M.USE_LINE = '^(%s*)<<(.-)>>%s*$'
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

function M.is_chunk_block(block)
  return block.t == 'CodeBlock' and block.text:match('^<<.->>=') ~= nil
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

local function parse_chunk(code, fail)
  local lines = M.split_lines(code)
  local name = lines[1]:match(M.CHUNK_HEADER)
  if not name then return nil end
  local last = lines[#lines]
  if not last:match('^@%s*$') and not last:match('^@ %%def ') then
    fail('chunk <<' .. name .. '>> does not end with @ (run make lint)')
  end
  local body = {}
  for i = 2, #lines - 1 do body[#body + 1] = lines[i] end
  local defs = {}
  for id in (last:match('^@ %%def (.*)$') or ''):gmatch('%S+') do
    defs[#defs + 1] = id
  end
  return {name = name, lines = body, defs = defs}
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
  local book = setmetatable({chunks = {}, by_name = {}, uses_of = {}, ids = {},
                             identifiers = {}, labels = {}, fail = fail}, Book)
  local chapter, count = 0, 0
  doc:walk({
    Header = function(block)
      if block.level == 1 and not block.classes:includes('unnumbered') then
        chapter, count = chapter + 1, 0
      end
      if block.identifier ~= '' then
        book.labels[block.identifier] = {
          kind = block.level == 1 and 'Chapter' or 'Section',
          level = block.level, chapter = chapter}
      end
    end,
    CodeBlock = function(block)
      if not M.is_chunk_block(block) then return end
      local chunk = parse_chunk(block.text, fail)
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
  for _, chunk in ipairs(book.chunks) do
    for _, line in ipairs(chunk.lines) do
      local _, used = line:match(M.USE_LINE)
      if used then
        if not book.by_name[used] then
          fail('chunk <<' .. chunk.name .. '>> ' .. chunk.number ..
               ' uses undefined fragment <<' .. used .. '>>')
        end
        book.uses_of[used] = book.uses_of[used] or {}
        table.insert(book.uses_of[used], chunk)
      end
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

-- Chunks whose code mentions an identifier as a whole word, other than where
-- it is defined (operators and other non-words are listed without uses).
function Book:identifier_uses(id)
  if not id:match('^[%a_][%w_]*$') then return {} end
  local result, skip = {}, {}
  for _, chunk in ipairs(self.identifiers[id]) do skip[chunk] = true end
  local pattern = '%f[%w_]' .. id .. '%f[^%w_]'
  for _, chunk in ipairs(self.chunks) do
    if not skip[chunk] then
      for _, line in ipairs(chunk.lines) do
        if not line:match(M.USE_LINE) and line:find(pattern) then
          result[#result + 1] = chunk
          break
        end
      end
    end
  end
  return result
end

return M
