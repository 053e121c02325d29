// Exercise calls: what a chapter's tests/chNN/exercise_calls.h includes to
// declare its calls (rpc.h, with the bytes of encoding.h and the kept objects
// of kept.h) and, in the builds that hold tests, to declare the tests that
// use them (exercise_test.h). The worker (LRT_WORKER) compiles the calls
// alone: it serves them and holds no test, nor GoogleTest.
//
// Included by calls.h (the lrt library's calls) and directly by a book that
// is not lrt (the exercise tools' fixture, tests/tools/exercises/): it needs
// nothing of the library.

#ifndef LRT_TESTS_CALLS_CORE_H
#define LRT_TESTS_CALLS_CORE_H

#include "calls/rpc.h"

#ifndef LRT_WORKER
#include "calls/exercise_test.h"
#endif

#endif  // LRT_TESTS_CALLS_CORE_H
