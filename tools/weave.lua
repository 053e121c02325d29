--[[
weave.lua: the pandoc filter that turns lrt's chapters into a literate book.

Every ```cpp block that starts with `<<Name>>=` is a noweb code chunk. This
filter numbers the chunks per chapter (2.7 is chapter 2's seventh), typesets
each with a `<Name> =` or `<Name> +=` header, highlighted C++, fragment uses
shown as `<Name 2.3>` and linked to their definition, and a footer that says
where the fragment is used, where it continues and what it defines, with page
numbers. At the end of the book it writes an Index of Fragments and an Index
of Identifiers (from noweb's `@ %def` lines).

It also resolves cross-references written as @sec:id, @fig:id, @eq:id and
@tbl:id, and numbered equations written as `$$ ... $$ {#eq:id}`; a reference
to a label that does not exist stops the build (no "??" in the book).

Before it changes anything, it checks its own reading of the chunks against
noweb's (/usr/lib/noweb/markup): if the two disagree, the book would show code
that is not the code that is compiled, so the build fails instead.

Code is highlighted here, through pandoc.write, so that fragment uses can be
turned into links inside the highlighted text. No code block reaches the LaTeX
writer, so the highlighting macros come from tools/weave.sh.
]]

local CHUNK_HEADER = '^<<(.+)>>=%s*$'
local USE_LINE = '^(%s*)<<(.-)>>%s*$'
-- Lua patterns have no alternation (a|b): shown_lines() checks the two words.
local EXERCISE_MARKER = '^%s*// (%u+) (%u+)%s*$'

local function fail(message)
  io.stderr:write('weave.lua: ' .. message .. '\n')
  os.exit(1)
end

local function latex_escape(s)
  return (s:gsub('[\\{}$&#^_%%~<>]', {
    ['\\'] = '\\textbackslash{}', ['{'] = '\\{', ['}'] = '\\}', ['$'] = '\\$',
    ['&'] = '\\&', ['#'] = '\\#', ['^'] = '\\^{}', ['_'] = '\\_',
    ['%'] = '\\%', ['~'] = '\\textasciitilde{}', ['<'] = '\\textless{}',
    ['>'] = '\\textgreater{}',
  }))
end

local function unescape_noweb(s)
  return (s:gsub('@<<', '<<'))
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

local function split_lines(text)
  local lines = {}
  for line in (text .. '\n'):gmatch('(.-)\n') do lines[#lines + 1] = line end
  return lines
end

-------------------------------------------------------------------------------
-- Reading the chunks

local chunks = {}        -- in book order: {name, number, label, lines, defs}
local by_name = {}       -- name -> list of chunks defining it
local uses_of = {}       -- name -> list of chunks that use it
local name_ids = {}      -- name -> short id used in LaTeX macro names
local identifiers = {}   -- identifier -> {chunk that defines it}
local labels = {}        -- label -> kind of target, for cross-references

local function parse_chunk(code)
  local lines = split_lines(code)
  local name = lines[1]:match(CHUNK_HEADER)
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

local function is_chunk_block(block)
  return block.t == 'CodeBlock' and block.text:match('^<<.->>=')
end

-- Walks the document once (in document order, into divs too), numbering
-- chunks by chapter and collecting the labels that references may target.
local function collect(doc)
  local chapter, count = 0, 0
  doc:walk({
    Header = function(block)
      if block.level == 1 and not block.classes:includes('unnumbered') then
        chapter, count = chapter + 1, 0
      end
      if block.identifier ~= '' then
        labels[block.identifier] = block.level == 1 and 'Chapter' or 'Section'
      end
    end,
    CodeBlock = function(block)
      if not is_chunk_block(block) then return end
      local chunk = parse_chunk(block.text)
      if chapter == 0 then
        fail('chunk <<' .. chunk.name .. '>> stands before the first chapter')
      end
      count = count + 1
      chunk.number = chapter .. '.' .. count
      chunk.label = 'chunk:' .. chunk.number
      chunks[#chunks + 1] = chunk
      if not by_name[chunk.name] then
        by_name[chunk.name] = {}
        name_ids[chunk.name] = 'f' .. (#chunks)
      end
      table.insert(by_name[chunk.name], chunk)
      for _, id in ipairs(chunk.defs) do
        identifiers[id] = identifiers[id] or {}
        table.insert(identifiers[id], chunk)
      end
    end,
    RawBlock = function(block)
      if block.format ~= 'latex' then return end
      for label in block.text:gmatch('\\label{([^}]+)}') do
        labels[label] = label:match('^fig:') and 'Figure' or
                        label:match('^tbl:') and 'Table' or 'Section'
      end
    end,
  })
  for _, chunk in ipairs(chunks) do
    for _, line in ipairs(chunk.lines) do
      local _, used = line:match(USE_LINE)
      if used then
        if not by_name[used] then
          fail('chunk <<' .. chunk.name .. '>> ' .. chunk.number ..
               ' uses undefined fragment <<' .. used .. '>>')
        end
        uses_of[used] = uses_of[used] or {}
        table.insert(uses_of[used], chunk)
      end
    end
  end
end

-------------------------------------------------------------------------------
-- The cross-check against noweb

-- Reads noweb's markup output into a list of {name, text} chunks.
local function noweb_chunks(files)
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

local function cross_check()
  local files = {}
  for _, file in ipairs(PANDOC_STATE.input_files) do files[#files + 1] = file end
  local theirs = noweb_chunks(files)
  local n = math.max(#theirs, #chunks)
  for i = 1, n do
    local mine, other = chunks[i], theirs[i]
    local where = mine and (' (fragment ' .. mine.number .. ')') or ''
    if not mine or not other or mine.name ~= other.name then
      fail(string.format('chunk %d%s: noweb reads <<%s>> but the weave reads <<%s>>; '
        .. 'is a chunk outside a ```cpp fence, in a list, or in a quote?', i, where,
        other and other.name or 'nothing', mine and mine.name or 'nothing'))
    end
    local my_text = unescape_noweb(table.concat(mine.lines, '\n'))
    local their_text = table.concat(other.lines, '\n')
    if my_text ~= their_text then
      fail('chunk <<' .. mine.name .. '>> ' .. mine.number .. ': noweb and the weave '
           .. 'read different code:\n--- noweb\n' .. their_text .. '\n--- weave\n'
           .. my_text)
    end
  end
end

-------------------------------------------------------------------------------
-- Typesetting a chunk

local function ref(chunk)
  return '\\chunkref{' .. chunk.label .. '}{' .. chunk.number .. '}'
end

local function ref_list(list)
  local seen, parts = {}, {}
  for _, chunk in ipairs(list) do
    if not seen[chunk] then
      seen[chunk] = true
      parts[#parts + 1] = ref(chunk)
    end
  end
  return table.concat(parts, ', ')
end

local function is_root(name)
  return not uses_of[name]
end

-- The code with exercise markers removed (the solution book shows solutions).
local function shown_lines(chunk)
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

local function highlight(lines)
  local placeholders = {}
  for i, line in ipairs(lines) do
    local indent, used = line:match(USE_LINE)
    if used then
      placeholders[#placeholders + 1] = used
      lines[i] = indent .. 'LRTFRAGMENTUSE' .. #placeholders .. 'X'
    else
      lines[i] = unescape_noweb(line)
    end
  end
  local code = pandoc.CodeBlock(table.concat(lines, '\n'), {class = 'cpp'})
  local latex = pandoc.write(pandoc.Pandoc({code}), 'latex')
  return (latex:gsub('LRTFRAGMENTUSE(%d+)X', function(i)
    return '\\fraguse{' .. name_ids[placeholders[tonumber(i)]] .. '}'
  end))
end

local function render_chunk(chunk)
  local defs = by_name[chunk.name]
  local first = defs[1]
  local parts = {}
  local function add(s) parts[#parts + 1] = s end
  local continuation = chunk ~= first
  add(string.format('\\begin{fragment}\\fragheader{%s}{%s}{%s}{%s}',
    chunk.label, chunk.number, name_ids[chunk.name], continuation and 'cont' or 'def'))
  add(highlight(shown_lines(chunk)))
  local notes = {}
  if is_root(chunk.name) then
    notes[#notes + 1] = '\\fragnote{File}{\\texttt{tangled/' .. latex_escape(chunk.name)
                        .. '}}'
  else
    notes[#notes + 1] = '\\fragnote{Used in}{' .. ref_list(uses_of[chunk.name]) .. '}'
  end
  if continuation then
    notes[#notes + 1] = '\\fragnote{Continues}{' .. ref(first) .. '}'
  end
  local later = {}
  local after = false
  for _, other in ipairs(defs) do
    if after then later[#later + 1] = other end
    if other == chunk then after = true end
  end
  if #later > 0 then
    notes[#notes + 1] = '\\fragnote{Continued in}{' .. ref_list(later) .. '}'
  end
  if #chunk.defs > 0 then
    local ids = {}
    for _, id in ipairs(chunk.defs) do
      ids[#ids + 1] = '\\identdef{' .. latex_escape(id) .. '}'
    end
    notes[#notes + 1] = '\\fragnote{Defines}{' .. table.concat(ids, ', ') .. '}'
  end
  add('\\fragfooter{' .. table.concat(notes, '\\fragsep ') .. '}\\end{fragment}')
  return pandoc.RawBlock('latex', table.concat(parts, '\n'))
end

local function render_plain_code(block)
  local lines = split_lines(block.text)
  for i, line in ipairs(lines) do lines[i] = unescape_noweb(line) end
  local code = pandoc.CodeBlock(table.concat(lines, '\n'), block.attr)
  return pandoc.RawBlock('latex', pandoc.write(pandoc.Pandoc({code}), 'latex'))
end

-------------------------------------------------------------------------------
-- The indexes

local function sorted_keys(t)
  local keys = {}
  for k in pairs(t) do keys[#keys + 1] = k end
  table.sort(keys, function(a, b)
    local la, lb = a:lower(), b:lower()
    if la == lb then return a < b end
    return la < lb
  end)
  return keys
end

local function fragment_index()
  local out = {'\\begin{fragmentindex}'}
  for _, name in ipairs(sorted_keys(by_name)) do
    local entry = '\\fragindexentry{' .. name_ids[name] .. '}{' ..
                  ref_list(by_name[name]) .. '}{'
    if is_root(name) then
      entry = entry .. 'file \\texttt{tangled/' .. latex_escape(name) .. '}'
    else
      entry = entry .. 'used in ' .. ref_list(uses_of[name])
    end
    out[#out + 1] = entry .. '}'
  end
  out[#out + 1] = '\\end{fragmentindex}'
  return table.concat(out, '\n')
end

-- Chunks whose code mentions an identifier as a whole word, other than where
-- it is defined (operators and other non-words are listed without uses).
local function identifier_uses(id, defining)
  if not id:match('^[%a_][%w_]*$') then return {} end
  local result, skip = {}, {}
  for _, chunk in ipairs(defining) do skip[chunk] = true end
  local pattern = '%f[%w_]' .. id .. '%f[^%w_]'
  for _, chunk in ipairs(chunks) do
    if not skip[chunk] then
      for _, line in ipairs(chunk.lines) do
        if not line:match(USE_LINE) and line:find(pattern) then
          result[#result + 1] = chunk
          break
        end
      end
    end
  end
  return result
end

local function identifier_index()
  local out = {'\\begin{identifierindex}'}
  for _, id in ipairs(sorted_keys(identifiers)) do
    local uses = identifier_uses(id, identifiers[id])
    out[#out + 1] = '\\identindexentry{' .. latex_escape(id) .. '}{' ..
                    ref_list(identifiers[id]) .. '}{' ..
                    (#uses > 0 and ('used in ' .. ref_list(uses)) or '') .. '}'
  end
  out[#out + 1] = '\\end{identifierindex}'
  return table.concat(out, '\n')
end

local function fragment_names()
  local out = {}
  for name, id in pairs(name_ids) do
    out[#out + 1] = '\\fragname{' .. id .. '}{' .. latex_escape(name) .. '}{' ..
                    by_name[name][1].label .. '}{' .. by_name[name][1].number .. '}'
  end
  table.sort(out)
  return table.concat(out, '\n')
end

-------------------------------------------------------------------------------
-- Cross-references and equations

local missing = {}

local function crossref(cite)
  if #cite.citations ~= 1 then return nil end
  local id = cite.citations[1].id
  local kind = id:match('^(%a+):')
  if not (kind == 'sec' or kind == 'fig' or kind == 'eq' or kind == 'tbl') then
    return nil
  end
  if not labels[id] then
    missing[#missing + 1] = id
    return nil
  end
  if kind == 'eq' then
    return pandoc.RawInline('latex', '\\hyperref[' .. id .. ']{Equation~(\\ref*{' ..
                            id .. '})}')
  end
  return pandoc.RawInline('latex', '\\hyperref[' .. id .. ']{' .. labels[id] ..
                          '~\\ref*{' .. id .. '}}')
end

-- `$$ x $$ {#eq:id}` arrives as Math followed by Str "{#eq:id}".
local function number_equations(inlines)
  local out, i = {}, 1
  while i <= #inlines do
    local el = inlines[i]
    if el.t == 'Math' and el.mathtype == 'DisplayMath' then
      local j = i + 1
      while inlines[j] and (inlines[j].t == 'Space' or inlines[j].t == 'SoftBreak') do
        j = j + 1
      end
      local label = inlines[j] and inlines[j].t == 'Str' and
                    inlines[j].text:match('^{#(eq:[%w_:%-]+)}$')
      if label then
        out[#out + 1] = pandoc.RawInline('latex', '\\begin{equation}' .. el.text ..
                                         '\\label{' .. label .. '}\\end{equation}')
        i = j + 1
      else
        out[#out + 1] = el
        i = i + 1
      end
    else
      out[#out + 1] = el
      i = i + 1
    end
  end
  return out
end

local function collect_equation_labels(doc)
  doc:walk({Str = function(s)
    local label = s.text:match('^{#(eq:[%w_:%-]+)}$')
    if label then labels[label] = 'Equation' end
  end, Image = function(img)
    if img.identifier ~= '' then labels[img.identifier] = 'Figure' end
  end})
end

-------------------------------------------------------------------------------

function Pandoc(doc)
  local rendered = 0
  collect(doc)
  cross_check()
  collect_equation_labels(doc)

  doc = doc:walk({
    Inlines = number_equations,
  })
  doc = doc:walk({
    Cite = crossref,
    Str = function(s)
      -- `<<` in T1-encoded text is a guillemet ligature: break it up.
      if not s.text:find('@<<', 1, true) then return nil end
      local parts = {}
      for i, piece in ipairs(split_on(s.text, '@<<')) do
        if i > 1 then parts[#parts + 1] = pandoc.RawInline('latex', '<{}<') end
        if piece ~= '' then parts[#parts + 1] = pandoc.Str(piece) end
      end
      return parts
    end,
    Code = function(c)
      if c.text:find('@<<', 1, true) then c.text = unescape_noweb(c.text); return c end
    end,
    CodeBlock = function(block)
      if is_chunk_block(block) then
        rendered = rendered + 1  -- this walk meets chunks in collect()'s order
        return render_chunk(chunks[rendered])
      end
      return render_plain_code(block)
    end,
  })
  if #missing > 0 then
    fail('references to undefined labels: ' .. table.concat(missing, ', '))
  end

  table.insert(doc.blocks, 1, pandoc.RawBlock('latex', fragment_names()))
  doc.blocks:insert(pandoc.RawBlock('latex', '\\backmatter'))
  doc.blocks:insert(pandoc.RawBlock('latex', fragment_index()))
  doc.blocks:insert(pandoc.RawBlock('latex', identifier_index()))
  return doc
end
