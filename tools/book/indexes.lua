--[[
indexes.lua: what the book's indexes and each fragment's footer say, apart
from how they are set. The PDF (tools/book/weave.lua) and the web edition
(tools/book/html.lua) show the same entries, the one with page numbers, the
other with links: they are built here once, so that the two cannot come to
list different things, and each filter only formats them.

Every list of chunks here names each chunk once, in book order (a fragment
used twice in one chunk is used in it once).

  indexes.fragments(book)    the Index of Fragments, one entry a fragment:
                             {name, chunks = its pieces, file = 'tangled/NAME'
                             for a root fragment, used_in = the chunks that use
                             it for any other}
  indexes.identifiers(book)  the Index of Identifiers, one entry an
                             identifier of `@ %def` lines: {id, chapter, nth
                             (1 for the first entry of its name, 2, ...),
                             chunks = the chunks that define it, used_in = the
                             chunks whose code has it as a word and which use
                             it rather than another of its name (below)}
  indexes.identifier_entry(book, chunk, id)
                             the entry of the identifier id that chunk defines
  indexes.notes(book, chunk) a chunk's footer: {file or used_in, as above,
                             continues, continued_in = the pieces of its
                             fragment just before and after it (or nil),
                             defines = the identifiers it defines}
  indexes.lister(show_chunk, show_file)
                             list(chunks) and destination(entry) as text

Both indexes are sorted by name without regard to case (fragments.sorted_keys).

One name may be several identifiers: `axis` a local variable in one chapter
and a member of a node in another, `Intersect` a method of boxes, shapes and
trees. The index cannot tell them apart by their spelling, so it goes by
where they stand, as the code is compiled: chapter N's code is compiled with
the chapters before it and without those after it, and a chapter's code is
compiled whole, whatever the order in which the prose shows it. So:

  - the definitions of a name in one chapter are one identifier (overloads,
    a class and its constructor, a declaration and its definition);
  - a word in a chunk of chapter N is a use of the identifier of the last
    chapter up to N that defines the name; a use earlier in that chapter than
    the definition counts too (the prose may show a call before the
    function);
  - a word in a chapter before every chapter that defines the name is some
    other thing of that name and is no use at all.
]]

local fragments = require('fragments')

local M = {}

local function distinct(chunks)
  local seen, out = {}, {}
  for _, chunk in ipairs(chunks) do
    if not seen[chunk] then
      seen[chunk] = true
      out[#out + 1] = chunk
    end
  end
  return out
end

-- Where a fragment goes: the library file it is tangled to (a root, which no chunk
-- uses), else the chunks that use it. Sets entry.file or entry.used_in.
local function destination(book, name, entry)
  if book:is_root(name) then
    entry.file = name
  else
    entry.used_in = distinct(book.uses_of[name])
  end
  return entry
end

-- How an edition lists chunks and fragments' destinations in its footers and
-- indexes, given how it shows one chunk (a page number, a link) and a file
-- name: two functions, list(chunks), the chunks separated by commas, and
-- destination(entry), an entry's file or used_in as text.
function M.lister(show_chunk, show_file)
  local function list(chunks)
    local parts = {}
    for _, chunk in ipairs(chunks) do parts[#parts + 1] = show_chunk(chunk) end
    return table.concat(parts, ', ')
  end
  local function destination(entry)
    if entry.file then return show_file(entry.file) end
    return list(entry.used_in)
  end
  return list, destination
end

function M.fragments(book)
  local entries = {}
  for _, name in ipairs(fragments.sorted_keys(book.by_name)) do
    entries[#entries + 1] = destination(book, name,
                                        {name = name, chunks = distinct(book.by_name[name])})
  end
  return entries
end

-- The identifiers of one name, given its uses, as entries (see the top).
local function identifiers_of(book, id, rank)
  local groups, by_chapter = {}, {}
  for _, chunk in ipairs(distinct(book.identifiers[id])) do
    local group = by_chapter[chunk.chapter]
    if not group then
      group = {id = id, chapter = chunk.chapter, nth = #groups + 1, chunks = {}, used_in = {}}
      by_chapter[chunk.chapter] = group
      groups[#groups + 1] = group
    end
    group.chunks[#group.chunks + 1] = chunk
  end
  for _, chunk in ipairs(distinct(book:identifier_uses(id))) do
    local owner
    for _, group in ipairs(groups) do
      if rank[group.chapter] <= rank[chunk.chapter] then owner = group end
    end
    if owner then owner.used_in[#owner.used_in + 1] = chunk end
  end
  return groups
end

function M.identifiers(book)
  if book.identifier_entries then return book.identifier_entries end
  local rank, chapters, entries, of_chunk = {}, 0, {}, {}
  for _, chunk in ipairs(book.chunks) do
    if not rank[chunk.chapter] then
      chapters = chapters + 1
      rank[chunk.chapter] = chapters
    end
  end
  for _, id in ipairs(fragments.sorted_keys(book.identifiers)) do
    for _, entry in ipairs(identifiers_of(book, id, rank)) do
      entries[#entries + 1] = entry
      for _, chunk in ipairs(entry.chunks) do
        of_chunk[chunk] = of_chunk[chunk] or {}
        of_chunk[chunk][id] = entry
      end
    end
  end
  book.identifier_entries, book.identifier_entry_of = entries, of_chunk
  return entries
end

function M.identifier_entry(book, chunk, id)
  M.identifiers(book)
  return book.identifier_entry_of[chunk][id]
end

function M.notes(book, chunk)
  local previous, next = book:neighbours(chunk)
  return destination(book, chunk.name, {continues = previous, continued_in = next,
                                        defines = chunk.defs})
end

return M
