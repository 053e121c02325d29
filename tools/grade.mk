# Classroom grading (tools/grade.py; DESIGN.md section 7, docs/grading.md).
# Included by the Makefile, so this runs from the repository root:
#
#   make grade SUBMISSION=path [OUT=dir] [GRADE_FLAGS="--time-limit 5 ..."]
#                       grade one submission (a directory, .tar.gz or .zip of
#                       edited chapters): results.json (Gradescope), junit.xml
#                       and results.txt in OUT (default build/grade/NAME)
#   make grade-batch SUBMISSIONS=dir [OUT=dir]
#                       every subdirectory or archive of dir is one student:
#                       OUT/NAME/ each, and OUT/grades.csv (default build/grade/batch)
#
# GRADE_FLAGS passes options through: --time-limit S, --memory-limit MB,
# --allow-changes-outside-exercises, --cxxflags ... (tools/grade.py --help).

.PHONY: grade grade-batch

GRADE_CACHE = $(BUILD)/grade/cache

grade: | deps
	@if [ -z "$(SUBMISSION)" ]; then echo "make grade: give SUBMISSION=path" >&2; exit 2; fi
	python3 tools/grade.py --cache $(GRADE_CACHE) $(if $(OUT),--out $(OUT)) $(GRADE_FLAGS) \
	    $(SUBMISSION)

grade-batch: | deps
	@if [ -z "$(SUBMISSIONS)" ]; then echo "make grade-batch: give SUBMISSIONS=dir" >&2; \
	    exit 2; fi
	python3 tools/grade.py --cache $(GRADE_CACHE) --batch $(SUBMISSIONS) \
	    $(if $(OUT),--out $(OUT)) $(GRADE_FLAGS)
