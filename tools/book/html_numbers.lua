--[[
html_numbers.lua: the numbers of the web edition's headings, figures, tables
and equations, as LaTeX gives them in the PDF: chapters 1, 2, ... and
appendices A, B, ...; sections to the third level (2.10.4); figures, tables
and numbered equations by chapter (Figure 2.3, Equation (2.3)). The HTML
writer knows none of these, so tools/book/html.lua counts them here; both
editions (tools/book/edition.lua) read them to set references in sequence as a
range.
]]

local fragments = require('fragments')

local M = {}

-- Numbers every heading (a span.secnum in front of its text, and the
-- attribute number), figure, table and numbered equation of doc: returns the
-- document and label -> the number a reference to it shows. A fourth-level
-- heading has no number of its own; a reference to it names the numbered
-- heading before it, as in the PDF. With decorate false the headings are
-- left alone: the PDF (tools/book/edition.lua) asks for the numbers only, to
-- tell which references run in sequence ("Sections 6.3-6.5").
function M.number_labels(doc, decorate)
  local numbers = {}
  local chapter, section, subsection, chapters, appendices = 0, 0, 0, 0, 0
  local current, counts = nil, {}
  local function count(kind, label)
    counts[kind] = (counts[kind] or 0) + 1
    numbers[label] = chapter .. '.' .. counts[kind]
  end
  doc = doc:walk({
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
      if shown and decorate ~= false then
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
  return doc, numbers
end

return M
