--[[
html_figures.lua: figures and tables of the web edition (tools/book/html.lua),
captioned with the PDF's numbers (tools/book/html_numbers.lua). A figure
drawn with TikZ in the chapters (raw LaTeX) is listed for the site writer
(tools/book/html_site.py), which compiles it on its own to SVG; a table in
raw LaTeX is read by pandoc's LaTeX reader; other raw LaTeX must only choose
where a printed page ends, which a web page lacks.

  local figures = require('html_figures').new(numbers, fail)
  figures.raw_latex(block), figures.image_figure(para), figures.drawings
]]

local text = require('html_text')

local raw = text.raw

local M = {}

-- Whether raw LaTeX only decides where a printed page ends (\newpage,
-- \clearpage, or such a choice made by \ifdim on the space left on the
-- page): a web page has no such end, so there is nothing to show.
local function page_break_only(latex)
  local rest = latex:gsub('\\ifdim.-\\fi', ''):gsub('\\par', '')
                    :gsub('\\newpage', ''):gsub('\\clearpage', ''):gsub('%s', '')
  return rest == ''
end

-- The LaTeX group that starts at latex's position open ("{...}"), without
-- its braces.
local function group_at(latex, open)
  local group = latex:match('^%b{}', open)
  return group and group:sub(2, -2)
end

function M.new(numbers, fail)
  local figures = {drawings = {}}   -- drawings: {name, latex} of each TikZ figure

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
    local inlines = pandoc.List({pandoc.Span({pandoc.Str('Figure\u{a0}' .. numbers[label] ..
                                                         ':')}, {class = 'figlabel'}),
                                 pandoc.Space()})
    inlines:extend(caption)
    blocks[#blocks + 1] = pandoc.Plain(inlines)
    blocks[#blocks + 1] = raw('</figcaption></figure>')
    return blocks
  end

  -- A figure in raw LaTeX: what stands between \begin{figure} (and
  -- \centering) and \caption is drawn on its own page by the site writer, as
  -- SVG.
  local function tikz_figure(latex)
    local label = latex:match('\\label{([^}]+)}')
    if not label then fail('a LaTeX figure without \\label: ' .. latex:sub(1, 200)) end
    local body = latex:match('\\begin{figure}%b[]%s*(.-)\\caption{') or
                 latex:match('\\begin{figure}%s*(.-)\\caption{')
    if not body then fail(label .. ': no drawing before \\caption') end
    body = body:gsub('^\\centering%s*', '')
    local name = label:gsub('[^%w%-]', '-')
    figures.drawings[#figures.drawings + 1] = {name = name, latex = body}
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

  -- A pandoc RawBlock filter: raw LaTeX as the web shows it.
  function figures.raw_latex(block)
    if block.format ~= 'latex' then return nil end
    if block.text:find('\\begin{figure}', 1, true) then return tikz_figure(block.text) end
    if block.text:find('\\begin{table}', 1, true) then return latex_table(block.text) end
    if page_break_only(block.text) then return {} end
    fail('raw LaTeX that the web edition cannot show: ' .. block.text:sub(1, 200))
  end

  -- A figure written in Markdown (fragments.is_figure).
  function figures.image_figure(para)
    local img = para.content[1]
    local label = img.identifier
    if label == '' then fail('a figure without an identifier: ' .. img.src) end
    local image = pandoc.Plain({pandoc.Image({pandoc.Str('Figure ' .. numbers[label])}, img.src,
                                             '', {class = 'figure-image'})})
    return figure_blocks(label, 'image', image, img.caption)
  end

  return figures
end

return M
