# The web edition: make html writes the book as a static site to
# $(BUILD)/html/ (open $(BUILD)/html/index.html; the folder can be copied to
# any static host). tools/html_site.py runs pandoc with tools/html.lua and
# writes the pages; the TikZ drawings it compiles to SVG are kept in
# $(HTML_CACHE), so that only a changed drawing is compiled again. Included
# by the Makefile, so this runs from the repository root.

.PHONY: html

HTML_OUT := $(BUILD)/html
HTML_CACHE ?= $(BUILD)/html-cache

html: $(HTML_OUT)/index.html

$(HTML_OUT)/index.html: book.md $(wildcard references.bib) $(CHAPTERS) tools/html_site.py \
                        tools/html.lua tools/fragments.lua tools/exercises.lua \
                        tools/tikz-preamble.tex $(wildcard tools/web/*) \
                        $(wildcard figures/*) | lint
	python3 tools/html_site.py --out $(HTML_OUT) --cache $(HTML_CACHE) book.md $(CHAPTERS)
