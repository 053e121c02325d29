#!/usr/bin/env bash
# weave.sh OUTDIR BOOK.md CHAPTER.md...: the book as OUTDIR/book.pdf.
#
# pandoc with tools/weave.lua writes LaTeX; pdflatex runs until the page
# references settle. The build fails on any LaTeX error, on references that
# stay undefined (no "??" in the book) and on code wider than its column.
# Run from the repository root, so figure paths resolve as in the chapters.
set -euo pipefail
out=$1; shift
mkdir -p "$out"
tools=$(dirname "$0")

# The filter highlights code itself, so no code block reaches pandoc's LaTeX
# writer and pandoc would not emit its highlighting macros: take them from a
# template that prints only those.
printf '$highlighting-macros$\n' > "$out/macros.template"
printf '```cpp\nint x;\n```\n' |
    pandoc -s -t latex --template="$out/macros.template" > "$out/preamble.tex"
cat "$tools/preamble.tex" >> "$out/preamble.tex"

pandoc "$@" --from markdown --lua-filter "$tools/exercises.lua" \
    --lua-filter "$tools/weave.lua" \
    --top-level-division=chapter --number-sections --toc \
    --include-in-header="$out/preamble.tex" \
    --standalone -o "$out/book.tex"

log=$out/book.log
for pass in 1 2 3 4; do
    if ! pdflatex -interaction=nonstopmode -halt-on-error -output-directory "$out" \
            "$out/book.tex" > "$out/pdflatex.out" 2>&1; then
        grep -A8 -m1 '^!' "$log" >&2 || tail -30 "$out/pdflatex.out" >&2
        echo "weave: pdflatex failed; see $log" >&2
        exit 1
    fi
    grep -q 'Rerun to get\|Label(s) may have changed' "$log" || break
done

status=0
if grep -q 'Reference .* undefined\|There were undefined references' "$log"; then
    grep 'Reference .* undefined' "$log" >&2
    echo "weave: undefined references in the book" >&2
    status=1
fi
# Overfull lines inside code (set in Verbatim, so TeX reports them "in
# alignment" or at the verbatim line) mean code runs into the margin.
if grep -A1 'Overfull \\hbox' "$log" | grep -q '\\T1/lmtt'; then
    grep -A1 'Overfull \\hbox' "$log" | grep -B1 '\\T1/lmtt' >&2
    echo "weave: code wider than its column" >&2
    status=1
fi
# Raster images must print at 300 pixels per inch or more; pdfimages gives
# each image's resolution at its printed size (columns 13 and 14).
low=$(pdfimages -list "$out/book.pdf" | awk 'NR > 2 && ($13 < 300 || $14 < 300)')
if [ -n "$low" ]; then
    printf '%s\n' "$low" >&2
    echo "weave: images printed at less than 300 ppi (page, ..., x-ppi, y-ppi above)" >&2
    status=1
fi
exit $status
