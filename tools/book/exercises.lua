--[[
exercises.lua: the pandoc filter that typesets exercise divs (docs/exercises.md).

    ::: {.exercise #ex-5.1 points=4 title="The slab test" section=sec:slab-test
         fragments="Slab test for one axis" hint="..."}      (on one line)
    The exercise's prose, and possibly the chunks it stubs.

    ::: hint
    A longer hint, in Markdown.
    :::
    :::

becomes a set-off block: "Exercise 5.1  The slab test ... 4 points", the
prose, "Hint: ...", and a line naming the section it practises, the fragments
to write and the tests to run (Ex5_1_*). In LaTeX it is typeset here; for the
web edition (tools/book/html.lua) it becomes a div.exercise with the same parts. tools/book/weave.sh runs it before
tools/book/weave.lua, so cross-references in the hint and the chunks inside the div
are handled there like any other. tools/exercises/markup.py checks the attributes
(make lint); this filter only shows them.

It also numbers the exercises. An exercise without a grade is a paragraph
that opens with a span of class problem holding its title:

    [Parallel treelets.]{.problem #ex:parallel-treelets} The treelets ...

shown as "6.1 Parallel treelets." (the number bold, the title in italics).
The exercises of a chapter, graded or not, are numbered in the order in which
they stand: chapter 6's are 6.1, 6.2, ... (appendices A.1, ...). A graded
exercise's id carries its number for the grader and the tests (ex-6.5,
Ex6_5_*), so it must be the number the count gives: one that is not stops the
build with the file and line of the div. The numbers are left in the
document's metadata (lrt-exercises: id -> number), from which
tools/book/fragments.lua takes the targets of references such as @ex-6.5 and
@ex:parallel-treelets ("Exercise 6.5").
]]

package.path = pandoc.path.directory(PANDOC_SCRIPT_FILE) .. '/?.lua;' .. package.path
local latex_escape = require('latex_text').escape

local function markdown_blocks(text)
  return pandoc.read(text, 'markdown').blocks
end

local function markdown_inlines(text)
  local blocks = markdown_blocks(text)
  if #blocks == 1 and (blocks[1].t == 'Para' or blocks[1].t == 'Plain') then
    return blocks[1].content
  end
  return {pandoc.Str(text)}
end

local function append(list, items)
  for _, item in ipairs(items) do list[#list + 1] = item end
end

-- The hint as blocks, "Hint:" set in front of its first paragraph.
local function hint_blocks(div)
  local hint = {}
  if div.attributes.hint and div.attributes.hint ~= '' then
    append(hint, markdown_blocks(div.attributes.hint))
  end
  for _, block in ipairs(div.content) do
    if block.t == 'Div' and block.classes:includes('hint') then
      append(hint, block.content)
    end
  end
  if #hint == 0 then return hint end
  local label = pandoc.Emph({pandoc.Str('Hint:')})
  if hint[1].t == 'Para' or hint[1].t == 'Plain' then
    table.insert(hint[1].content, 1, pandoc.Space())
    table.insert(hint[1].content, 1, label)
  else
    table.insert(hint, 1, pandoc.Para({label}))
  end
  return hint
end

local function fragments(div)
  local names = {}
  for name in (div.attributes.fragments or ''):gmatch('[^;]+') do
    name = name:gsub('^%s+', ''):gsub('%s+$', '')
    if name ~= '' then names[#names + 1] = name end
  end
  return names
end

-------------------------------------------------------------------------------
-- Numbering

local function fail(message)
  io.stderr:write('exercises.lua: ' .. message .. '\n')
  os.exit(1)
end

-- "file:line" of the first line of the input that holds text (plain) or,
-- for an id ("#ex-6.5"), the id followed by a space or a brace, so that an
-- error names the exercise's place; the input files if no line does.
local function locate(text)
  local function holds(line)
    if not text:match('^#') then return line:find(text, 1, true) end
    return line:find(text .. ' ', 1, true) or line:find(text .. '}', 1, true)
  end
  for _, file in ipairs(PANDOC_STATE.input_files) do
    local handle = io.open(file)
    if handle then
      local n = 0
      for line in handle:lines() do
        n = n + 1
        if holds(line) then
          handle:close()
          return file .. ':' .. n
        end
      end
      handle:close()
    end
  end
  return table.concat(PANDOC_STATE.input_files, ', ')
end

local numbers   -- id -> the number the count gives it

local function number_exercises(doc)
  numbers = {}
  local chapter, count, appendices = 0, 0, 0
  local function next_number(what)
    if chapter == 0 then fail(locate(what) .. ': an exercise before the first chapter') end
    count = count + 1
    return chapter .. '.' .. count
  end
  local function record(id, number)
    if numbers[id] then fail(locate('#' .. id) .. ': a second exercise with the id ' .. id) end
    numbers[id] = number
  end
  doc:walk({
    traverse = 'topdown',
    Header = function(h)
      if h.level ~= 1 then return nil end
      if h.classes:includes('appendix') then
        appendices, count = appendices + 1, 0
        chapter = string.char(string.byte('A') + appendices - 1)
      elseif not h.classes:includes('unnumbered') then
        chapter, count = chapter + 1, 0
      end
    end,
    Div = function(div)
      if not div.classes:includes('exercise') then return nil end
      local id = div.identifier
      local number = next_number('#' .. id)
      if id ~= 'ex-' .. number then
        fail(locate('#' .. id) .. ': the exercise ' .. (id == '' and 'without an id' or id)
             .. ' is exercise ' .. number .. ' of its chapter; its id must be ex-' .. number
             .. ' (the ungraded exercises before it count too)')
      end
      record(id, number)
    end,
    Span = function(span)
      if not span.classes:includes('problem') then return nil end
      local id = span.identifier
      if not id:match('^ex:[%w_%-]+$') then
        fail(locate(pandoc.utils.stringify(span.content)) .. ': the exercise "' ..
             pandoc.utils.stringify(span.content) .. '" needs an id ex:name ' ..
             '([Title.]{.problem #ex:name})')
      end
      local number = next_number('#' .. id)
      span.attributes.number = number
      record(id, number)
      return span
    end,
  })
  local meta = {}
  for id, number in pairs(numbers) do meta[id] = pandoc.MetaString(number) end
  doc.meta['lrt-exercises'] = pandoc.MetaMap(meta)
  return doc
end

-- An ungraded exercise's number and title.
local function problem(span)
  if not span.classes:includes('problem') then return nil end
  local number = numbers[span.identifier]
  if FORMAT:match('latex') then
    local out = {pandoc.RawInline('latex', '\\phantomsection\\label{' .. span.identifier ..
                                  '}\\textbf{' .. number .. '}'), pandoc.Space()}
    append(out, {pandoc.Emph(span.content)})
    return out
  end
  return pandoc.Span({pandoc.Strong({pandoc.Str(number)}), pandoc.Space(),
                      pandoc.Emph(span.content)},
                     pandoc.Attr(span.identifier, {'problem'}))
end

-------------------------------------------------------------------------------
-- Typesetting a graded exercise

local function exercise(div)
  if not div.classes:includes('exercise') then return nil end
  local id = div.identifier
  local number = id:match('^ex%-(.+)$') or id
  local points = tonumber(div.attributes.points or '')
  local points_text = points and (points .. (points == 1 and ' point' or ' points')) or ''
  local title = div.attributes.title or ''
  local section = div.attributes.section
  local suites = 'Ex' .. number:gsub('%.', '_') .. '_*'

  local content = {}
  for _, block in ipairs(div.content) do
    if not (block.t == 'Div' and block.classes:includes('hint')) then
      content[#content + 1] = block
    end
  end

  if not FORMAT:match('latex') then
    local heading = {pandoc.Strong({pandoc.Str('Exercise ' .. number)}), pandoc.Space()}
    append(heading, markdown_inlines(title))
    append(heading, {pandoc.Space(), pandoc.Span({pandoc.Str(points_text)}, {class = 'points'})})
    local blocks = {pandoc.Div({pandoc.Para(heading)}, {class = 'exercise-head'})}
    append(blocks, content)
    append(blocks, hint_blocks(div))
    -- The section and the fragments are a cross-reference and examples of
    -- fragments, which tools/book/html.lua turns into links with their numbers.
    local notes = {}
    local function add(label, inlines)
      if #notes > 0 then append(notes, {pandoc.Space(), pandoc.Str('·'), pandoc.Space()}) end
      append(notes, {pandoc.Strong({pandoc.Str(label)}), pandoc.Space()})
      append(notes, inlines)
    end
    if section then
      add('Practises:', {pandoc.Cite({pandoc.Str('@' .. section)},
                                     {pandoc.Citation(section, 'NormalCitation')})})
    end
    local names = {}
    for _, name in ipairs(fragments(div)) do
      if #names > 0 then append(names, {pandoc.Str(','), pandoc.Space()}) end
      names[#names + 1] = pandoc.Code(name, {class = 'fragment-use'})
    end
    if #names > 0 then add('Write:', names) end
    add('Tests:', {pandoc.Code(suites)})
    blocks[#blocks + 1] = pandoc.Div({pandoc.Para(notes)}, {class = 'exercise-notes'})
    return pandoc.Div(blocks, pandoc.Attr(id, {'exercise'}))
  end

  local head = '\\par\\bigskip\\noindent\\rule{\\linewidth}{0.4pt}\\par\\nopagebreak' ..
    '\\noindent\\phantomsection\\label{' .. id .. '}\\textbf{Exercise ' .. number ..
    '}\\enspace{}'
  local heading = {pandoc.RawInline('latex', head)}
  append(heading, markdown_inlines(title))
  heading[#heading + 1] = pandoc.RawInline('latex', '\\hfill\\textsf{' .. points_text ..
                                           '}\\par\\nopagebreak')
  local blocks = {pandoc.Plain(heading)}
  append(blocks, content)
  append(blocks, hint_blocks(div))

  local notes = {}
  if section then
    notes[#notes + 1] = '\\textsf{Practises:}~\\hyperref[' .. section ..
                        ']{\\S\\ref*{' .. section .. '}}'
  end
  local names = {}
  for _, name in ipairs(fragments(div)) do
    names[#names + 1] = '\\fragmentname{' .. latex_escape(name) .. '}{}'
  end
  if #names > 0 then
    notes[#notes + 1] = '\\textsf{Write:}~' .. table.concat(names, ', ')
  end
  notes[#notes + 1] = '\\textsf{Tests:}~\\texttt{' .. latex_escape(suites) .. '}'
  blocks[#blocks + 1] = pandoc.RawBlock('latex',
    '{\\par\\footnotesize\\raggedright\\noindent ' .. table.concat(notes, '\\quad ') ..
    '\\par}\\nopagebreak\\noindent\\rule{\\linewidth}{0.4pt}\\par\\bigskip')
  return blocks
end

return {{Pandoc = number_exercises}, {Div = exercise, Span = problem}}
