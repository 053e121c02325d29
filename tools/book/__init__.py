"""The book: weaving the chapters into the PDF and the web edition (pandoc with
the Lua filters), and checking the layout of the woven pages."""
