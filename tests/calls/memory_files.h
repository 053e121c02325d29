// Exercise calls, files in memory: the worker may open no file (its
// system-call filter, wall.cpp), so a call that must hand the code a file by
// its path registers the file's bytes here, and the worker's link routes
// fopen() to them (worker.cpp, -Wl,--wrap=fopen).
//
// Included by worker.cpp (the fopen wrap) and by the exercise_calls.h of a
// chapter whose calls hand over files (chapter 3's PLY files), which uses it
// only in the worker (LRT_WORKER).

#ifndef LRT_TESTS_CALLS_MEMORY_FILES_H
#define LRT_TESTS_CALLS_MEMORY_FILES_H

#include <map>
#include <string>

namespace lrt {
namespace calls {

// The files, by path: fopen() of one of these paths in the worker opens a
// read-only stream of its bytes.
inline std::map<std::string, std::string> &MemoryFiles() {
    static std::map<std::string, std::string> files;
    return files;
}

}  // namespace calls
}  // namespace lrt

#endif  // LRT_TESTS_CALLS_MEMORY_FILES_H
