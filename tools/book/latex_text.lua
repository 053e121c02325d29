--[[
latex_text.lua: text as the PDF's filters (tools/book/weave.lua and
tools/book/exercises.lua) write it into LaTeX, so that a fragment's name, say,
is escaped alike in a chunk's header and in an exercise's "Write:" line.
]]

local M = {}

-- s as LaTeX text: the characters that LaTeX gives a meaning of its own, and
-- < and > (which T1 text fonts set as other characters), as commands.
function M.escape(s)
  return (s:gsub('[\\{}$&#^_%%~<>]', {
    ['\\'] = '\\textbackslash{}', ['{'] = '\\{', ['}'] = '\\}', ['$'] = '\\$',
    ['&'] = '\\&', ['#'] = '\\#', ['^'] = '\\textasciicircum{}', ['_'] = '\\_',
    ['%'] = '\\%', ['~'] = '\\textasciitilde{}', ['<'] = '\\textless{}',
    ['>'] = '\\textgreater{}',
  }))
end

return M
