#!/usr/bin/env bash
# weave.sh OUTDIR BOOK.md CHAPTER.md...: the book as OUTDIR/book.pdf.
#
# pandoc with tools/book/weave.lua writes LaTeX, with citations and References by
# pandoc's citeproc (the bibliography and its style are named in BOOK.md's
# metadata); pdflatex runs until the page references settle. The build fails
# on any LaTeX error, on references or citations that stay undefined (no "??"
# in the book), on code wider than its column, and on a fragment that came
# apart on the page (tools/book/layout_check.py).
# Run from the repository root, so figure paths resolve as in the chapters.
set -euo pipefail
out=$1; shift
mkdir -p "$out"
tools=$(dirname "$0")

# The filter highlights code itself, so no code block reaches pandoc's LaTeX
# writer and pandoc would not emit its highlighting macros: take them from a
# template that prints only those.
printf '$highlighting-macros$\n' > "$out/macros.template"
# tools/book/highlight.theme prints in greyscale: bold keywords, grey comments.
printf '```cpp\nint x;\n```\n' |
    pandoc -s -t latex --highlight-style="$tools/highlight.theme" \
        --template="$out/macros.template" > "$out/preamble.tex"
cat "$tools/tikz-preamble.tex" "$tools/preamble.tex" >> "$out/preamble.tex"

# citeproc runs after weave.lua, which resolves @sec:, @fig:, @eq: and @tbl:
# itself; citeproc only warns about a key that the bibliography lacks.
pandoc "$@" --from markdown --lua-filter "$tools/measured.lua" \
    --lua-filter "$tools/exercises.lua" \
    --lua-filter "$tools/weave.lua" --citeproc \
    --top-level-division=chapter --number-sections --toc \
    --include-in-header="$out/preamble.tex" \
    --standalone -o "$out/book.tex" 2> "$out/pandoc.err" || {
    cat "$out/pandoc.err" >&2; exit 1; }
cat "$out/pandoc.err" >&2
if grep -q 'Citeproc: citation .* not found' "$out/pandoc.err"; then
    echo "weave: citations of keys that the bibliography does not have" >&2
    exit 1
fi

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
python3 "$tools/layout_check.py" "$out/book.layout" || status=1
exit $status
