--[[
edition.lua: what the PDF (tools/book/weave.lua) and the web edition
(tools/book/html.lua) do alike to the book's document, with the typesetting
left to the filter that calls it, so that the two walk the book the same way
and differ only in what they write.

  local book = edition.read(doc, fail)
      the chunks as tools/book/fragments.lua reads them, checked against
      noweb's reading of the same input files.

  doc = edition.typeset(doc, book, typeset, fail)
      numbers the equations, then typesets every chunk, plain code block,
      fragment sample, cross-reference and figure through typeset's functions:

        equation(math, label)          a numbered display equation (inline)
        reference(id, kind, target)    @sec:/@fig:/@eq:/@tbl: (book:reference)
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
]]

local fragments = require('fragments')

local M = {}

function M.read(doc, fail)
  local book = fragments.read(doc, fail)
  local files = {}
  for _, file in ipairs(PANDOC_STATE.input_files) do files[#files + 1] = file end
  book:cross_check(files)
  return book
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
      local id, kind, target = book:reference(cite)
      if id then return typeset.reference(id, kind, target) end
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
