--[[
measured.lua: a measured number printed where a chapter names it.

A chapter writes a number that a measurement gave as a span of its name,
`[L2.sah.final.camera]{.m}`, and this filter puts the value in its place, as
tools/bench/book_numbers.py formats it from the file that book.md's metadata
names (`measurements: figures/data/bvh-measurements.json`). The text, its
tables and the plot thus read one file and cannot disagree. Both editions run
it first: weave.sh for the PDF, html_site.py for the web.

A name that the data lacks stops the weave; make lint has already named the
chapter's file and line (book_numbers.py --check).
]]

local NUMBERS_PY = (debug.getinfo(1, 'S').source:match('^@(.*)[/\\]') or '.')
                   .. '/../bench/book_numbers.py'
local values, source

local function fail(message)
  error('measured.lua: ' .. message, 0)
end

local function read_values(meta)
  if not meta.measurements then return nil end
  source = pandoc.utils.stringify(meta.measurements)
  local ok, out = pcall(pandoc.pipe, 'python3', {NUMBERS_PY, '--lua', source}, '')
  if not ok then fail('tools/bench/book_numbers.py --lua ' .. source .. ' failed: ' .. tostring(out)) end
  local chunk, err = load(out, 'book_numbers.py', 't', {})
  if not chunk then fail('cannot load what book_numbers.py wrote: ' .. err) end
  values = chunk()
  return nil
end

local function measured_number(span)
  if not span.classes:includes('m') then return nil end
  local name = pandoc.utils.stringify(span.content)
  if not values then
    fail('[' .. name .. ']{.m}: the book names no measurements file (metadata "measurements")')
  end
  local value = values[name]
  if not value then fail('no measured number named "' .. name .. '" in ' .. source) end
  return pandoc.Str(value)
end

return {{Meta = read_values}, {Span = measured_number}}
