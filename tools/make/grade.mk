# Classroom grading (tools/grading/grade.py; docs/grading.md).
# Included by the Makefile, so this runs from the repository root:
#
#   make grade SUBMISSION=path [CHAPTERS="05"] [OUT=dir] [GRADE_FLAGS="..."]
#                       grade one submission (a directory, .tar.gz or .zip of
#                       edited chapters): results.json (Gradescope), junit.xml
#                       and results.txt in OUT (default build/grade/NAME)
#   make grade-batch SUBMISSIONS=dir [CHAPTERS="05"] [OUT=dir] [ROSTER=file.csv]
#                       every subdirectory or archive of dir is one submission:
#                       OUT/NAME/ each, OUT/grades.csv and OUT/gradebook.csv
#                       (default build/grade/batch); a NAME that is not a plain
#                       name (..., .hidden, spaces) is refused; ROSTER says whose
#                       each is (submission,student,login rows; default: NAME)
#
#   make gradescope [CHAPTERS="05" | PLAN=course.toml ASSIGNMENT=a1] [GRADE_FLAGS="..."]
#                       build/gradescope/autograder.zip, Gradescope's autograder
#                       (tools/grading/gradescope.py): it grades what CHAPTERS or the
#                       plan's assignment say, with GRADE_FLAGS
#
# PLAN=file ASSIGNMENT=name grades one assignment of a course plan
# (docs/course.md): its exercises, with the plan's points.
# CHAPTERS="02 05" grades the exercises of those chapters only, as make
# exercises CHAPTERS=... chooses them (default: the chapters of a kit's
# exercises.json, else every chapter with exercises).
#
# GRADE_FLAGS passes options through: --time-limit S, --memory-limit MB,
# --allow-changes-outside-exercises, --cxxflags ... (tools/grading/grade.py --help).

.PHONY: grade grade-batch gradescope

GRADE_CACHE = $(BUILD)/grade/cache
# The chapters given by number: CHAPTERS="02 05", CHOSEN_NUMBERS in the Makefile.
GRADE_CHAPTERS = $(CHOSEN_NUMBERS)
GRADE_PLAN = $(if $(PLAN),--plan $(PLAN))$(if $(ASSIGNMENT), --assignment $(ASSIGNMENT))

grade:
	@if [ -z "$(SUBMISSION)" ]; then echo "make grade: give SUBMISSION=path" >&2; exit 2; fi
	python3 tools/grading/grade.py --cache $(GRADE_CACHE) $(if $(OUT),--out $(OUT)) \
	    $(if $(GRADE_CHAPTERS),--chapters "$(GRADE_CHAPTERS)") $(GRADE_PLAN) $(GRADE_FLAGS) \
	    $(SUBMISSION)

grade-batch:
	@if [ -z "$(SUBMISSIONS)" ]; then echo "make grade-batch: give SUBMISSIONS=dir" >&2; \
	    exit 2; fi
	python3 tools/grading/grade.py --cache $(GRADE_CACHE) --batch $(SUBMISSIONS) \
	    $(if $(OUT),--out $(OUT)) $(if $(GRADE_CHAPTERS),--chapters "$(GRADE_CHAPTERS)") \
	    $(if $(ROSTER),--roster $(ROSTER)) $(GRADE_PLAN) $(GRADE_FLAGS)

gradescope:
	python3 tools/grading/gradescope.py --out $(BUILD)/gradescope/autograder.zip \
	    $(if $(GRADE_CHAPTERS),--chapters "$(GRADE_CHAPTERS)") $(GRADE_PLAN) -- $(GRADE_FLAGS)
