# The web edition: make html writes the book as a static site to
# $(BUILD)/html/ (open $(BUILD)/html/index.html; the folder can be copied to
# any static host). tools/book/html_site.py runs pandoc with tools/book/html.lua and
# writes the pages; the TikZ drawings it compiles to SVG are kept in
# $(HTML_CACHE), so that only a changed drawing is compiled again. Included
# by the Makefile, so this runs from the repository root.

.PHONY: html

HTML_OUT := $(BUILD)/html
HTML_CACHE ?= $(BUILD)/html-cache

html: $(HTML_OUT)/index.html

$(HTML_OUT)/index.html: book.md $(wildcard references.bib) $(CHAPTERS) tools/book/html_site.py \
                        $(wildcard tools/book/html*.lua) tools/book/fragments.lua \
                        tools/noweb/chunks.py tools/book/exercises.lua tools/book/latex_text.lua \
                        tools/book/edition.lua tools/book/indexes.lua \
                        tools/book/measured.lua tools/bench/book_numbers.py $(wildcard $(MEASUREMENTS)) \
                        tools/book/tikz-preamble.tex $(wildcard tools/book/web/*) \
                        $(wildcard figures/*) | $(LINTED)
	$(LINT_NUMBERS)
	python3 tools/book/html_site.py --out $(HTML_OUT) --cache $(HTML_CACHE) book.md $(CHAPTERS)
