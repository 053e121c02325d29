// Exercise calls, the calls themselves: the one way a graded exercise's
// tests reach the code they grade (docs/grading.md).
//
// A chapter's tests/chNN/exercise_calls.h lists, as plain functions in
// namespace lrt::direct, the operations its exercise tests perform on the
// library (intersect this box with this ray, build this BVH, ...), and turns
// each into a call lrt::ex::Name(...) with LRT_EXERCISE_CALL(Name), which
// also registers the function (Operations()) for whoever serves calls.
//
// One source, three builds. In `make test` a call is a plain function call.
// In the judge (LRT_JUDGE, judge.cpp) it becomes a request to the worker:
// Call() encodes the arguments and asks Answer(), and decodes the reply. In
// the worker (LRT_WORKER, worker.cpp) ServeCall() decodes a request, runs the
// function on the student's code and encodes its reply (reply.h).
//
// Included by core.h (so by every chapter's exercise_calls.h), worker.cpp,
// judge.cpp and exercise_test.h.

#ifndef LRT_TESTS_CALLS_RPC_H
#define LRT_TESTS_CALLS_RPC_H

#include "calls/encoding.h"
#include "calls/kept.h"
#include "calls/reply.h"

#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace lrt {
namespace calls {

using Serve = std::string (*)(Reader &);
struct Operation {
    const char *name;
    Serve serve;
};
inline std::vector<Operation> &Operations() {
    static std::vector<Operation> operations;
    return operations;
}
struct Registration {
    Registration(const char *name, Serve serve) {
        Operations().push_back({name, serve});
    }
};

template <auto F>
struct Signature;
template <typename R, typename... A, R (*F)(A...)>
struct Signature<F> {
    using Result = R;
    using Arguments = std::tuple<std::decay_t<A>...>;
};

// Decodes the arguments of F, calls it, and encodes its result.
template <auto F>
std::string ServeCall(Reader &r) {
    typename Signature<F>::Arguments args;
    std::apply([&](auto &...a) { (Get(r, a), ...); }, args);
    if (r.Remaining() != 0) throw Malformed("arguments left over");
    return Reply([&](Writer &w) { Put(w, std::apply(F, args)); });
}

#ifdef LRT_JUDGE
// judge.cpp: the reply of the worker to this call (or a speculative reply,
// computed by `speculate` with the book's code, that only steers the test
// until the worker's reply is known).
std::string Answer(const std::string &request,
                   const std::function<std::string()> &speculate);
// Throws what the reply says was thrown, or fails the test on a reply that
// is not Ok; returns a reader positioned at the result.
void Unpack(const std::string &reply, const char *name, Reader *r);
#endif

#ifndef LRT_JUDGE
// In a course's student kit (docs/course.md), the stub of an exercise that a
// later assignment sets says so: "Exercise ex-2.12 comes with a later
// assignment: ..." (tools/exercises/markup.py, LATER_STUB). A test that reaches such
// a stub, through a call or in its own checks, can check nothing until then,
// so `make test` skips it with that message instead of failing it. A call
// throws it on as a Later, not a std::logic_error, so that no EXPECT_THROW of
// the test takes it for the error it expects. The judge never skips: in
// grading, every exercise but the graded one is the book's.
struct Later {
    std::string message;
};

inline bool IsLater(const std::logic_error &e) {
    const char *what = e.what();
    const char *words = std::strstr(what, " comes with a later assignment: ");
    return std::strncmp(what, "Exercise ", 9) == 0 && words &&
           !std::memchr(what + 9, ' ', size_t(words - what - 9));
}
#endif

template <auto F, typename... Args>
typename Signature<F>::Result Call(const char *name, Args &&...args) {
#ifdef LRT_JUDGE
    typename Signature<F>::Arguments tuple(std::forward<Args>(args)...);
    Writer w;
    Put(w, std::string(name));
    std::apply([&](auto &...a) { (Put(w, a), ...); }, tuple);
    std::string reply = Answer(w.bytes, [&] {
        Reader r(w.bytes);
        std::string skip;
        Get(r, skip);
        return ServeCall<F>(r);
    });
    Reader r(reply);
    Unpack(reply, name, &r);
    typename Signature<F>::Result result;
    Get(r, result);
    if (r.Remaining() != 0) throw Malformed("a reply longer than its result");
    return result;
#else
    (void)name;
    try {
        return F(std::forward<Args>(args)...);
    } catch (const std::logic_error &e) {
        if (IsLater(e)) throw Later{e.what()};
        throw;
    }
#endif
}

}  // namespace calls
}  // namespace lrt

// LRT_EXERCISE_CALL(Name) turns lrt::direct::Name into the call
// lrt::ex::Name, which the exercise's tests use.
#define LRT_EXERCISE_CALL(Name)                                               \
    namespace lrt {                                                           \
    namespace ex {                                                            \
    inline ::lrt::calls::Registration lrtRegistration##Name(                  \
        #Name, &::lrt::calls::ServeCall<&::lrt::direct::Name>);               \
    template <typename... Args>                                               \
    auto Name(Args &&...args) {                                               \
        return ::lrt::calls::Call<&::lrt::direct::Name>(                      \
            #Name, std::forward<Args>(args)...);                              \
    }                                                                         \
    }                                                                         \
    }

#endif  // LRT_TESTS_CALLS_RPC_H
