--[[
html_fragments.lua: the book's code in the web edition (tools/book/html.lua):
chunks with the PDF's headers, numbers, uses and "Used in / Continues /
Continued in / Defines" lines, and an anchor each (#chunk:2.7); fragments
shown as examples in the prose; code blocks that are no chunk; and the Index
of Fragments and the Index of Identifiers, whose entries tools/book/indexes.lua
builds for both editions. Links are written "#id"; tools/book/html_site.py
points each at the page that holds id.

  local code = require('html_fragments').new(book)
]]

local fragments = require('fragments')
local indexes = require('indexes')
local text = require('html_text')

local escape, raw = text.escape, text.raw

local M = {}

-- The anchor of an entry of the Index of Identifiers: "ident-" and its
-- characters, each one that is not a letter, digit or _ written as -hex
-- (operator[] is ident-operator-5b-5d); a second identifier of the same name
-- (tools/book/indexes.lua) adds "--" and the chapter that defines it.
local function ident_anchor(entry)
  return 'ident-' .. entry.id:gsub('[^%w_]', function(c)
    return string.format('-%02x', c:byte())
  end) .. (entry.nth > 1 and ('--' .. entry.chapter) or '')
end

local function chunk_link(chunk, html, class)
  return string.format('<a%s href="#%s" title="%s">%s</a>',
    class and (' class="' .. class .. '"') or '', chunk.label,
    escape('⟨' .. chunk.name .. '⟩ ' .. chunk.number), html or chunk.number)
end

-- Links to chunks (their numbers), and a fragment's file or users.
local link_list, destination = indexes.lister(chunk_link, function(file)
  return '<code>' .. escape(file) .. '</code>'
end)

-- pandoc numbers the lines of a code block with anchors (cb1-1, ...) that
-- would repeat in every block written on its own: they are dropped.
local function without_line_anchors(html)
  return (html:gsub('<a href="#cb%d+%-%d+" aria%-hidden="true" tabindex="%-1"></a>', '')
              :gsub('<span id="cb%d+%-%d+">', '<span>')
              :gsub('<div class="sourceCode" id="cb%d+">', '<div class="sourceCode">'))
end

local function note(key, value)
  return '<span class="fragnote"><span class="notekey">' .. key .. ':</span> ' ..
         value .. '</span>'
end

function M.new(book)
  local code = {}

  local function use_html(name)
    local first = book.by_name[name][1]
    return chunk_link(first, '⟨<span class="fragusename">' .. escape(name) ..
                      '</span> <span class="fragnum">' .. first.number .. '</span>⟩',
                      'fraguse')
  end

  local function footer(chunk)
    local notes, about = {}, indexes.notes(book, chunk)
    notes[#notes + 1] = note(about.file and 'File' or 'Used in', destination(about))
    if about.continues then notes[#notes + 1] = note('Continues', chunk_link(about.continues)) end
    if about.continued_in then
      notes[#notes + 1] = note('Continued in', chunk_link(about.continued_in))
    end
    if #about.defines > 0 then
      local ids = {}
      for _, id in ipairs(about.defines) do
        local entry = indexes.identifier_entry(book, chunk, id)
        ids[#ids + 1] = '<a class="ident" href="#' .. ident_anchor(entry) .. '"><code>' ..
                        escape(id) .. '</code></a>'
      end
      notes[#notes + 1] = note('Defines', table.concat(ids, ', '))
    end
    return '<div class="fragfoot">' .. table.concat(notes, ' ') .. '</div>'
  end

  local function header_line(chunk, number_link)
    local op = chunk == book:first(chunk) and '≡' or '+≡'
    local number = number_link and chunk_link(chunk, nil, 'fragnum') or
                   '<span class="fragnum">' .. chunk.number .. '</span>'
    return '<div class="fraghead"><a class="fragname" href="#' .. chunk.label .. '">⟨' ..
           escape(chunk.name) .. '⟩</a>&nbsp;' .. op .. ' ' .. number .. '</div>'
  end

  function code.chunk(chunk)
    local html = fragments.highlight(fragments.shown_lines(chunk), 'html5', use_html)
    return raw('<div class="fragment" id="' .. chunk.label .. '">' .. header_line(chunk) ..
               without_line_anchors(html) .. footer(chunk) .. '</div>')
  end

  function code.plain_code(block)
    return raw(without_line_anchors(pandoc.write(pandoc.Pandoc({block}), 'html5')))
  end

  -- A fragment shown as an example in the prose (see tools/book/weave.lua),
  -- given its first chunk; a header alone in its paragraph is set off as a
  -- fragment of its own.
  function code.sample_number(first)
    return pandoc.RawInline('html', chunk_link(first))
  end

  function code.sample_use(first)
    return pandoc.RawInline('html', use_html(first.name))
  end

  function code.sample_header(first)
    return pandoc.RawInline('html', header_line(first, true))
  end

  function code.sample_paragraph(html)
    if html:match('^<div class="fraghead"') then
      return raw('<div class="fragment sample">' .. html .. '</div>')
    end
  end

  -- The two indexes, given their entries (indexes.fragments, indexes.identifiers).
  function code.fragment_index(entries)
    local out = {'<ul class="index fragment-index">'}
    for _, entry in ipairs(entries) do
      out[#out + 1] = '<li><span class="fragname">⟨' .. escape(entry.name) .. '⟩</span> ' ..
                      link_list(entry.chunks) .. '; ' .. (entry.file and 'file ' or 'used in ') ..
                      destination(entry) .. '</li>'
    end
    out[#out + 1] = '</ul>'
    return table.concat(out, '\n')
  end

  function code.identifier_index(entries)
    local out = {'<ul class="index identifier-index">'}
    for _, entry in ipairs(entries) do
      out[#out + 1] = '<li id="' .. ident_anchor(entry) .. '"><code>' .. escape(entry.id) ..
                      '</code> ' .. link_list(entry.chunks) ..
                      (#entry.used_in > 0 and ('; used in ' .. link_list(entry.used_in)) or '') ..
                      '</li>'
    end
    out[#out + 1] = '</ul>'
    return table.concat(out, '\n')
  end

  return code
end

return M
