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
                             identifier of an `@ %def` line: {id, chunks = the
                             chunks that define it, used_in = the other chunks
                             whose code has it as a word}
  indexes.notes(book, chunk) a chunk's footer: {file or used_in, as above,
                             continues, continued_in = the pieces of its
                             fragment just before and after it (or nil),
                             defines = the identifiers it defines}
  indexes.lister(show_chunk, show_file)
                             list(chunks) and destination(entry) as text

Both indexes are sorted by name without regard to case (fragments.sorted_keys).
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

function M.identifiers(book)
  local entries = {}
  for _, id in ipairs(fragments.sorted_keys(book.identifiers)) do
    entries[#entries + 1] = {id = id, chunks = distinct(book.identifiers[id]),
                             used_in = distinct(book:identifier_uses(id))}
  end
  return entries
end

function M.notes(book, chunk)
  local previous, next = book:neighbours(chunk)
  return destination(book, chunk.name, {continues = previous, continued_in = next,
                                        defines = chunk.defs})
end

return M
