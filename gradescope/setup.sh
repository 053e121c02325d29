#!/usr/bin/env bash
# Gradescope autograder setup: Gradescope runs this as root in its Ubuntu/Debian
# image, with this repository unpacked in /autograder/source (zip the repository
# with gradescope/setup.sh and gradescope/run_autograder at the top, for example
# `cp gradescope/* . && zip -r autograder.zip .`, or keep them here: both work).
# tools/deps.sh grade installs the Debian packages grading needs (the
# compiler, noweb, GoogleTest, bubblewrap, ccache), not those of the book.
set -euo pipefail
cd "$(dirname "$(readlink -f "$0")")"
[ -f tools/deps.sh ] || cd ..
apt-get update
tools/deps.sh grade
# Warm the build cache with the reference solution, so that a student whose
# chapter compiles to the same code is graded without a compile.
mkdir -p /tmp/lrt-warm/chapters
cp chapters/[0-9][0-9]-*.md /tmp/lrt-warm/chapters/
python3 tools/grade.py --out /tmp/lrt-warm-out --quiet /tmp/lrt-warm || true
rm -rf /tmp/lrt-warm /tmp/lrt-warm-out
