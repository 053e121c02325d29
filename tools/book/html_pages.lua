--[[
html_pages.lua: how the web edition (tools/book/html.lua) cuts the book into
pages, and what the manifest says of them: the title block of the front
page, the pages with their headings, and the entries of the search box.

A page is a section (a second-level heading), or a whole chapter where the
chapter is short; a long section is cut at its third-level headings. The
front matter is the front page (index.html), where <!--lrt-contents-->
marks the place of the contents; each back-matter chapter (References, the
indexes) is a page of its own.
]]

local text = require('html_text')

local html_of, raw = text.html_of, text.raw

-- A chapter of fewer words than this is one page; a section of more words
-- than that is cut into pages at its third-level headings.
local SHORT_CHAPTER_WORDS = 2500
local LONG_SECTION_WORDS = 6000

local M = {}

local function words(blocks)
  local n = 0
  for _, block in ipairs(blocks) do
    for _ in pandoc.utils.stringify(block):gmatch('%S+') do n = n + 1 end
  end
  return n
end

-- The page file of a heading: the chapter's number and the heading's id
-- without "sec:" (and without the chapter's number, where the id repeats it).
local function page_file(chapter, header, fail)
  local slug = header.identifier:gsub('^sec:', ''):gsub('^' .. chapter .. '%-', '')
  if slug == '' then fail('a heading without an identifier: ' ..
                          pandoc.utils.stringify(header)) end
  return (chapter ~= '' and (chapter .. '-') or '') .. slug:gsub('[^%w%-_.]', '-') .. '.html'
end

local function heading_entry(h)
  local inlines = pandoc.List(h.content)
  if h.attributes.number then   -- the number span and the space after it
    inlines = inlines:filter(function(_, i) return i > 2 end)
  end
  return {id = h.identifier, level = h.level, number = h.attributes.number or '',
          title = html_of(inlines), text = text.text_of(inlines)}
end

-- The front matter, each chapter, each back-matter chapter: the groups of
-- top-level blocks that pages are cut from. Headings numbered by
-- tools/book/html_numbers.lua carry the attribute number.
local function chapter_groups(blocks)
  local groups, group, chapters = {}, nil, 0
  for _, block in ipairs(blocks) do
    local numbered = block.t == 'Header' and block.attributes.number ~= nil
    if numbered then chapters = chapters + 1 end
    if block.t == 'Header' and block.level == 1 and (numbered or chapters > 0) then
      group = {header = block, blocks = {}}
      groups[#groups + 1] = group
    elseif not group then
      group = {front = true, blocks = {}}
      groups[#groups + 1] = group
    end
    table.insert(group.blocks, block)
  end
  return groups
end

-- Runs of blocks, each from a heading of level.
local function cut(list, level)
  local runs, run = {}, nil
  for _, block in ipairs(list) do
    if not run or (block.t == 'Header' and block.level == level) then
      run = {}
      runs[#runs + 1] = run
    end
    run[#run + 1] = block
  end
  return runs
end

local function new_page(file, kind, run, chapter)
  local head = run[1].t == 'Header' and run[1] or nil
  local page = {file = file, kind = kind, chapter = chapter, blocks = run,
                number = head and head.attributes.number or '',
                title = '', text = '', headings = {}}
  if head then
    local entry = heading_entry(head)
    page.title, page.text = entry.title, entry.text
  end
  for _, block in ipairs(run) do
    if block.t == 'Header' and block.identifier ~= '' then
      page.headings[#page.headings + 1] = heading_entry(block)
    end
  end
  return page
end

-- Splits the top-level blocks into pages (see the top of this file): the
-- blocks with a marker <!--lrt-page FILE--> in front of each page, and the
-- list of pages.
function M.paginate(blocks, fail)
  local pages = {}
  local function add_page(file, kind, run, chapter)
    pages[#pages + 1] = new_page(file, kind, run, chapter)
  end
  for _, g in ipairs(chapter_groups(blocks)) do
    if g.front then
      table.insert(g.blocks, raw('<!--lrt-contents-->'))
      add_page('index.html', 'front', g.blocks, '')
    elseif not g.header.attributes.number then
      add_page(page_file('', g.header, fail), 'back', g.blocks, '')
    else
      local number = g.header.attributes.number
      local chapter = tonumber(number) and string.format('%02d', tonumber(number)) or number
      if words(g.blocks) < SHORT_CHAPTER_WORDS then
        add_page(page_file(chapter, g.header, fail), 'chapter', g.blocks, chapter)
      else
        for i, run in ipairs(cut(g.blocks, 2)) do
          local kind = i == 1 and 'chapter' or 'section'
          local parts = {run}
          if i > 1 and words(run) > LONG_SECTION_WORDS then parts = cut(run, 3) end
          for j, part in ipairs(parts) do
            add_page(page_file(chapter, part[1], fail), j == 1 and kind or 'subsection', part,
                     chapter)
          end
        end
      end
    end
  end

  local out, seen = {}, {}
  for _, page in ipairs(pages) do
    if seen[page.file] then fail('two pages would be ' .. page.file) end
    seen[page.file] = true
    out[#out + 1] = raw('<!--lrt-page ' .. page.file .. '-->')
    for _, block in ipairs(page.blocks) do out[#out + 1] = block end
    page.blocks = nil
  end
  return out, pages
end

-- What the search box finds: every numbered or labelled heading, every
-- fragment (by its name) and every identifier (at its first definition),
-- given the entries of the two indexes (tools/book/indexes.lua).
function M.search_entries(pages, fragment_entries, identifier_entries)
  local entries = {}
  for _, page in ipairs(pages) do
    for _, h in ipairs(page.headings) do
      entries[#entries + 1] = {k = 's', t = h.text, n = h.number, id = h.id}
    end
  end
  for _, entry in ipairs(fragment_entries) do
    local first = entry.chunks[1]
    entries[#entries + 1] = {k = 'f', t = entry.name, n = first.number, id = first.label}
  end
  for _, entry in ipairs(identifier_entries) do
    local first = entry.chunks[1]
    entries[#entries + 1] = {k = 'i', t = entry.id, n = first.number, id = first.label}
  end
  return entries
end

-- The front page's title block, from the book's metadata.
function M.title_block(meta)
  local parts = {'<header class="titleblock">'}
  local function add(field, tag, class)
    if meta[field] then
      parts[#parts + 1] = '<' .. tag .. ' class="' .. class .. '">' ..
                          html_of(pandoc.utils.type(meta[field]) == 'Inlines' and meta[field]
                                  or {pandoc.Str(pandoc.utils.stringify(meta[field]))}) ..
                          '</' .. tag .. '>'
    end
  end
  add('title', 'h1', 'title')
  add('subtitle', 'p', 'subtitle')
  add('author', 'p', 'author')
  add('date', 'p', 'date')
  parts[#parts + 1] = '</header>'
  return raw(table.concat(parts, '\n'))
end

return M
