#!/usr/bin/env bash
# Check that the Debian 12 packages lrt builds with are present. Run as root, it
# installs what is missing; otherwise it prints the one apt-get line and fails.
# Each check looks for a file the package ships, so a half-installed TeX is caught.
set -euo pipefail

missing=()
need() {  # need PACKAGE TEST...: PACKAGE is missing unless the test succeeds
    local package=$1; shift
    "$@" >/dev/null 2>&1 || missing+=("$package")
}
have_sty() { kpsewhich "$1" | grep -q .; }

# What grading needs (tools/deps.sh grade: a Gradescope image needs no more):
# the tangle, the compiler and GoogleTest for the judge, bubblewrap for the
# sandbox, ccache to compile unchanged code once.
need g++           command -v g++
need python3       command -v python3
need noweb         command -v notangle
need libgtest-dev  test -f /usr/include/gtest/gtest.h
need bubblewrap    command -v bwrap
need ccache        command -v ccache
if [ "${1:-}" != grade ]; then
    need make          command -v make
    need pandoc        command -v pandoc
    need libbenchmark-dev test -f /usr/include/benchmark/benchmark.h
    need poppler-utils command -v pdftotext
    need texlive-latex-recommended command -v pdflatex
    need texlive-latex-recommended have_sty fancyvrb.sty
    need texlive-fonts-recommended have_sty pcrr8t.tfm
    need texlive-latex-extra       have_sty framed.sty
    need texlive-pictures          have_sty tikz.sty
    need texlive-pictures          have_sty pgfplots.sty
    need lmodern                   have_sty lmodern.sty
    need libstb-dev    test -f /usr/include/stb/stb_image_write.h
    # The book's citation style (book.md names the file).
    need citation-style-language-styles \
        test -f /usr/share/citation-style-language/styles/chicago-author-date.csl
    # The web edition (make html) copies MathJax into the site; its tests drive
    # Debian's chromium with chromedriver through python3-selenium.
    need libjs-mathjax    test -f /usr/share/javascript/mathjax/MathJax.js
    need chromium         test -x /usr/bin/chromium
    need chromium-driver  test -x /usr/bin/chromedriver
    need python3-selenium test -f /usr/lib/python3/dist-packages/selenium/__init__.py
fi
# make book-measurements (tools/deps.sh measure) counts instructions with
# callgrind and measures Embree beside lrt.
if [ "${1:-}" = measure ]; then
    need valgrind command -v valgrind
fi
# make bench BENCH_PEERS=embree (tools/deps.sh embree) measures Embree 3 beside lrt.
if [ "${1:-}" = embree ] || [ "${1:-}" = measure ]; then
    need libembree-dev test -f /usr/include/embree3/rtcore.h
fi
[ ${#missing[@]} -eq 0 ] && exit 0
packages=$(printf '%s\n' "${missing[@]}" | sort -u | tr '\n' ' ')
if [ "$(id -u)" -eq 0 ]; then
    # apt's and dpkg's output, thousands of lines on a fresh machine, goes to
    # a log that is shown only if the install fails.
    log=$(mktemp /tmp/lrt-deps.XXXXXX.log)
    echo "deps: installing $packages"
    echo "deps: (on a fresh machine about 450 MB to fetch, TeX Live and chromium the most of" \
         "it: a few minutes; apt's output goes to $log)"
    export DEBIAN_FRONTEND=noninteractive
    # shellcheck disable=SC2086
    if ! { apt-get update -q && apt-get install -y -q --no-install-recommends $packages; } \
            > "$log" 2>&1; then
        tail -n 30 "$log" >&2
        echo "deps: apt-get failed; its whole output is in $log" >&2
        exit 1
    fi
    rm -f "$log"
    # Check again: a package that installed but did not bring what we test for
    # must stop the build here, not in the middle of a LaTeX run.
    [ -z "${LRT_DEPS_RECHECK:-}" ] && LRT_DEPS_RECHECK=1 exec "$0" "$@"
    echo "deps: still missing after installing: $packages" >&2
    exit 1
else
    echo "lrt needs Debian packages that are not installed. Run:" >&2
    echo "    sudo apt-get install $packages" >&2
    exit 1
fi
