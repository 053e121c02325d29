#!/usr/bin/env bash
# Gradescope's autograder setup: Gradescope runs this as root in its
# Ubuntu/Debian image, with the zip that `make gradescope` writes unpacked in
# /autograder/source (this script at its top). It installs the Debian packages
# grading needs (tools/deps.sh grade: the compiler, noweb, GoogleTest,
# bubblewrap, ccache; nothing of the book's), then warms the build cache by
# grading the book's own chapters with the autograder's flags (grade_flags):
# the judges are built, and a student whose code for an exercise is the
# book's is graded without a compile. The book's chapters must score every
# point, or the autograder is broken and setup fails.
set -euo pipefail
cd "$(dirname "$(readlink -f "$0")")"
[ -f tools/deps.sh ] || cd ..
tools/deps.sh grade
warm=$(mktemp -d)
trap 'rm -rf "$warm"' EXIT
mkdir "$warm/book"
cp -r chapters "$warm/book/"
flags=()
[ -f grade_flags ] && flags+=(@grade_flags)
# shellcheck disable=SC2206
flags+=(${GRADE_FLAGS:-})
python3 tools/grading/grade.py --out "$warm/out" --quiet "${flags[@]}" "$warm/book"
python3 - "$warm/out/results.json" <<'PY'
import json, sys
data = json.load(open(sys.argv[1]))
if abs(data['score'] - data['max_score']) > 1e-6:
    sys.exit('setup: the book\'s own chapters score %g of %g: the autograder is broken'
             % (data['score'], data['max_score']))
print('setup: the book\'s chapters score %g of %g; build cache warm'
      % (data['score'], data['max_score']))
PY
