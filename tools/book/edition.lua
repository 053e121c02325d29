--[[
edition.lua: what the PDF (tools/book/weave.lua) and the web edition
(tools/book/html.lua) do alike to the book's document, with the typesetting
left to the filter that calls it, so that the two walk the book the same way
and differ only in what they write.

  local book = edition.read(doc, fail)
      the chunks as tools/book/fragments.lua reads them, checked against
      noweb's reading of the same input files, with the number of every label
      (tools/book/html_numbers.lua).

  doc = edition.typeset(doc, book, typeset, fail)
      numbers the equations, then typesets every chunk, plain code block,
      fragment sample, cross-reference and figure through typeset's functions:

        equation(math, label)          a numbered display equation (inline)
        number(item)                   the number a cross-reference shows
                                       (inlines): 6.3, (2.5) for an equation
        link(item, inlines)            inlines as a link to the item (inlines)
                                       (items as book:references gives them)
        sample_number(first), sample_use(first), sample_header(first)
                                       `Name`{.fragment-number} and the like,
                                       given the fragment's first chunk
        inline_code(code)              other inline code, noweb's @<< undone
        chunk(chunk)                   a chunk, from book.chunks
        plain_code(block)              a code block that is no chunk, as a
                                       CodeBlock with noweb's @<< undone
        figure(para)                   a Markdown figure (fragments.is_figure)
        sample_paragraph(text)         a paragraph that is nothing but a
                                       RawInline of this text: a block, or nil
                                       to leave it alone
        Str, RawBlock                  pandoc filter functions, as they are

      and fails on cross-references to labels the book lacks.

Cross-references are set here, alike in both editions, from the numbers
that the edition gives: one, @eq:a, as "Equation (2.5)", linked whole; several
in one citation, [@eq:a; @eq:b; @eq:c], as prose, "Equations (2.5), (2.6) and
(2.7)", each number linked; three or more sections, figures, tables or
exercises that run in sequence as a range, "Sections 6.3-6.5" (with an en
dash); [-@eq:a] without the noun, "(2.5)", where the prose names the thing
itself ("the implicit equation (3.5)"). A citation may group targets of one
kind only (sections, chapters, figures, ...).
]]

local fragments = require('fragments')
local html_numbers = require('html_numbers')

local M = {}

function M.read(doc, fail)
  local book = fragments.read(doc, fail)
  local files = {}
  for _, file in ipairs(PANDOC_STATE.input_files) do files[#files + 1] = file end
  book:cross_check(files)
  local _, numbers = html_numbers.number_labels(doc, false)
  for label, target in pairs(book.labels) do
    target.number = target.number or numbers[label]
  end
  return book
end

-------------------------------------------------------------------------------
-- Cross-references

local NOUNS = {eq = 'Equation', fig = 'Figure', tbl = 'Table', ex = 'Exercise'}
local PLURALS = {Appendix = 'Appendices'}
local NBSP = '\u{a0}'

local function noun(item)
  return NOUNS[item.kind] or item.target.kind
end

-- Does number b follow a (6.4 after 6.3, 2.10 after 2.9)?
local function follows(a, b)
  local head_a, last_a = tostring(a):match('^(.-)(%d+)$')
  local head_b, last_b = tostring(b):match('^(.-)(%d+)$')
  return head_a ~= nil and head_a == head_b and tonumber(last_b) == tonumber(last_a) + 1
end

-- The items (book:references) as inlines.
local function references(items, bare, typeset, fail)
  -- Two labels in one numbered section (fourth-level headings) show one number.
  local distinct, seen = {}, {}
  for _, item in ipairs(items) do
    if noun(item) ~= noun(items[1]) then
      fail('the citation of ' .. items[1].id .. ' and ' .. item.id .. ' mixes kinds (' ..
           noun(items[1]) .. ', ' .. noun(item) .. '): cite them apart')
    end
    local number = item.target.number
    if not number then fail('@' .. item.id .. ': a label without a number') end
    if not seen[number] then
      seen[number] = true
      distinct[#distinct + 1] = item
    end
  end
  local out = pandoc.List()
  local name = noun(distinct[1])
  if #distinct == 1 then
    if bare then return typeset.link(distinct[1], typeset.number(distinct[1])) end
    local shown = pandoc.List({pandoc.Str(name .. NBSP)})
    shown:extend(typeset.number(distinct[1]))
    return typeset.link(distinct[1], shown)
  end
  -- Runs of three or more in sequence become ranges, except of equations:
  -- "(2.5)-(2.7)" reads as an expression, so they are listed.
  local ranges = distinct[1].kind ~= 'eq'
  local parts, i = {}, 1
  while i <= #distinct do
    local j = i
    while ranges and distinct[j + 1] and
          follows(distinct[j].target.number, distinct[j + 1].target.number) do
      j = j + 1
    end
    if j - i >= 2 then
      parts[#parts + 1] = {distinct[i], distinct[j]}
      i = j + 1
    else
      parts[#parts + 1] = {distinct[i]}
      i = i + 1
    end
  end
  if not bare then out:insert(pandoc.Str((PLURALS[name] or name .. 's') .. NBSP)) end
  for k, part in ipairs(parts) do
    if k > 1 then
      if k == #parts then
        out:extend({pandoc.Space(), pandoc.Str('and'), pandoc.Space()})
      else
        out:extend({pandoc.Str(','), pandoc.Space()})
      end
    end
    out:extend(typeset.link(part[1], typeset.number(part[1])))
    if part[2] then
      out:insert(pandoc.Str('–'))
      out:extend(typeset.link(part[2], typeset.number(part[2])))
    end
  end
  return out
end

local SAMPLE = {['fragment-number'] = 'sample_number', ['fragment-use'] = 'sample_use',
                ['fragment-header'] = 'sample_header'}

-- A fragment shown as an example in the prose (see the comment at the top of
-- tools/book/weave.lua); nil for other inline code.
local function sample(code, book, typeset)
  local class = fragments.sample_class(code)
  if not class then return nil end
  local first = book:fragment(code.text, 'the example `' .. code.text .. '`{.' .. class .. '}')
  return typeset[SAMPLE[class]](first)
end

function M.typeset(doc, book, typeset, fail)
  local rendered = 0
  doc = doc:walk({
    Inlines = function(inlines)
      return fragments.number_equations(inlines, typeset.equation)
    end,
  })
  doc = doc:walk({
    Cite = function(cite)
      local items, bare = book:references(cite)
      if items then return references(items, bare, typeset, fail) end
    end,
    Str = typeset.Str,
    Code = function(c)
      local shown = sample(c, book, typeset)
      if shown then return shown end
      if c.text:find('@<<', 1, true) then c.text = fragments.unescape_noweb(c.text) end
      return typeset.inline_code(c)
    end,
    CodeBlock = function(block)
      if fragments.is_chunk_block(block) then
        rendered = rendered + 1  -- this walk meets chunks in the order read()
        return typeset.chunk(book.chunks[rendered])
      end
      local lines = fragments.split_lines(block.text)
      for i, line in ipairs(lines) do lines[i] = fragments.unescape_noweb(line) end
      return typeset.plain_code(pandoc.CodeBlock(table.concat(lines, '\n'), block.attr))
    end,
    Para = function(para)
      if fragments.is_figure(para) then return typeset.figure(para) end
      local only = #para.content == 1 and para.content[1]
      if only and only.t == 'RawInline' then return typeset.sample_paragraph(only.text) end
    end,
    RawBlock = typeset.RawBlock,
  })
  if #book.missing > 0 then
    fail('references to undefined labels: ' .. table.concat(book.missing, ', '))
  end
  if rendered ~= #book.chunks then
    fail('typeset ' .. rendered .. ' of ' .. #book.chunks .. ' chunks')
  end
  return doc
end

return M
