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

function Div(div)
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
