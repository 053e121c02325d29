--[[
html_text.lua: text for the web edition (tools/book/html.lua) from pandoc
elements and Lua values: HTML escapes, inlines as HTML or plain text, raw
HTML blocks, and the JSON of the manifest that tools/book/html_site.py reads.
]]

local fragments = require('fragments')

local M = {}

function M.escape(s)
  return (s:gsub('[&<>"]', {['&'] = '&amp;', ['<'] = '&lt;', ['>'] = '&gt;',
                            ['"'] = '&quot;'}))
end

-- Inlines as HTML, for the side bar and the titles of links: pandoc sets
-- their mathematics in HTML itself, under a class that MathJax leaves alone.
function M.html_of(inlines)
  return (pandoc.write(pandoc.Pandoc({pandoc.Plain(inlines)}), 'html5'):gsub('\n', ' ')
          :gsub('<span class="math inline">', '<span class="math-text">'))
end

function M.text_of(inlines)
  return (pandoc.write(pandoc.Pandoc({pandoc.Plain(inlines)}), 'plain'):gsub('%s+', ' ')
          :gsub('^ ', ''):gsub(' $', ''))
end

function M.raw(html)
  return pandoc.RawBlock('html', html)
end

-- JSON for the manifest: tables with [1] (or empty) are arrays, and the keys
-- of others are written in order, so that the same book gives the same
-- manifest. Characters that could end the <script> element are written as
-- \u escapes.
function M.json(value, fail)
  local kind = type(value)
  if kind == 'string' then
    return '"' .. value:gsub('[%c"\\<>&]', function(c)
      return string.format('\\u%04x', c:byte())
    end) .. '"'
  elseif kind == 'number' or kind == 'boolean' then
    return tostring(value)
  elseif kind == 'table' then
    local parts = {}
    if value[1] ~= nil or next(value) == nil then
      for _, item in ipairs(value) do parts[#parts + 1] = M.json(item, fail) end
      return '[' .. table.concat(parts, ',') .. ']'
    end
    for _, key in ipairs(fragments.sorted_keys(value)) do
      parts[#parts + 1] = M.json(key, fail) .. ':' .. M.json(value[key], fail)
    end
    return '{' .. table.concat(parts, ',') .. '}'
  end
  fail('cannot write a ' .. kind .. ' as JSON')
end

return M
