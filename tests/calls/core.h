// Exercise calls: the one way a graded exercise's tests reach the code they
// grade (docs/grading.md).
//
// A chapter's tests/chNN/exercise_calls.h (with calls.h) lists, as plain functions in
// namespace lrt::direct, the operations its exercise tests perform on the
// library (intersect this box with this ray, build this BVH, ...), and turns
// each into a call lrt::ex::Name(...) with LRT_EXERCISE_CALL(Name). The tests
// of an exercise use only those calls to reach the exercise's code, and are
// declared with EXERCISE_TEST instead of TEST.
//
// In `make test` a call is a plain function call. The grader compiles the same
// tests with LRT_JUDGE into the judge (tests/calls/judge.cpp), linked with the
// book's code: there every call becomes a message to a worker process that
// runs the student's code in a sandbox (tests/calls/worker.cpp), and the
// judge checks the answers. The process that decides a verdict never runs the
// student's code; the worker sees arguments, never a test's name or code.
//
// Arguments and results cross the boundary as bytes: arithmetic values bit
// for bit (NaNs and signed zeros included), strings, vectors, arrays, pairs,
// and structs that list their members with LRT_FIELDS(...); calls.h adds the
// library's geometry. This header needs nothing of the library, so that a
// book other than lrt's (the exercise tools' fixture) can use it.

#ifndef LRT_TESTS_CALLS_CORE_H
#define LRT_TESTS_CALLS_CORE_H

#ifndef LRT_WORKER
#include <gtest/gtest.h>
#endif

#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace lrt {
namespace calls {

// ---------------------------------------------------------------------------
// Bytes

// A reply or request that cannot be decoded: the worker's answer is wrong.
class Malformed : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

struct Writer {
    std::string bytes;
    void Raw(const void *p, size_t n) {
        bytes.append(static_cast<const char *>(p), n);
    }
};

class Reader {
  public:
    explicit Reader(const std::string &s)
        : p(s.data()), end(s.data() + s.size()) {}
    void Raw(void *out, size_t n) {
        if (size_t(end - p) < n) throw Malformed("truncated message");
        std::memcpy(out, p, n);
        p += n;
    }
    size_t Remaining() const { return size_t(end - p); }

  private:
    const char *p, *end;
};

// Structs list their members once, for both directions:
//   struct SlabHit { bool hit; Float t0, t1; LRT_FIELDS(hit, t0, t1) };
#define LRT_FIELDS(...)                                 \
    template <typename LrtVisit>                        \
    void Fields(LrtVisit &&lrtVisit) {                  \
        lrtVisit(__VA_ARGS__);                          \
    }

struct AnyVisit {
    template <typename... T>
    void operator()(T &...) const {}
};
template <typename T, typename = void>
struct HasFields : std::false_type {};
template <typename T>
struct HasFields<T, std::void_t<decltype(std::declval<T &>().Fields(AnyVisit()))>>
    : std::true_type {};

template <typename T>
std::enable_if_t<std::is_arithmetic_v<T> && !std::is_same_v<T, bool>> Put(
    Writer &w, const T &v) {
    w.Raw(&v, sizeof(v));
}
template <typename T>
std::enable_if_t<std::is_arithmetic_v<T> && !std::is_same_v<T, bool>> Get(
    Reader &r, T &v) {
    r.Raw(&v, sizeof(v));
}
inline void Put(Writer &w, bool v) { Put(w, uint8_t(v ? 1 : 0)); }
inline void Get(Reader &r, bool &v) {
    uint8_t b;
    Get(r, b);
    if (b > 1) throw Malformed("a bool that is neither 0 nor 1");
    v = b == 1;
}
template <typename T>
std::enable_if_t<std::is_enum_v<T>> Put(Writer &w, const T &v) {
    Put(w, int64_t(v));
}
template <typename T>
std::enable_if_t<std::is_enum_v<T>> Get(Reader &r, T &v) {
    int64_t i;
    Get(r, i);
    v = T(i);
}

inline void Put(Writer &w, const std::string &s) {
    Put(w, uint64_t(s.size()));
    w.Raw(s.data(), s.size());
}
inline void Get(Reader &r, std::string &s) {
    uint64_t n;
    Get(r, n);
    if (n > r.Remaining()) throw Malformed("a string longer than its message");
    s.resize(size_t(n));
    r.Raw(&s[0], size_t(n));
}

template <typename T>
void Put(Writer &w, const std::vector<T> &v);
template <typename T>
void Get(Reader &r, std::vector<T> &v);
template <typename T, size_t N>
void Put(Writer &w, const std::array<T, N> &a);
template <typename T, size_t N>
void Get(Reader &r, std::array<T, N> &a);
template <typename A, typename B>
void Put(Writer &w, const std::pair<A, B> &p);
template <typename A, typename B>
void Get(Reader &r, std::pair<A, B> &p);

template <typename T>
std::enable_if_t<HasFields<T>::value> Put(Writer &w, const T &v) {
    const_cast<T &>(v).Fields([&](auto &...f) { (Put(w, f), ...); });
}
template <typename T>
std::enable_if_t<HasFields<T>::value> Get(Reader &r, T &v) {
    v.Fields([&](auto &...f) { (Get(r, f), ...); });
}

template <typename T>
void Put(Writer &w, const std::vector<T> &v) {
    Put(w, uint64_t(v.size()));
    for (const T &x : v) Put(w, x);
}
template <typename T>
void Get(Reader &r, std::vector<T> &v) {
    uint64_t n;
    Get(r, n);
    // Every element takes at least a byte: a count larger than the rest of
    // the message is a lie, not a reason to allocate.
    if (n > r.Remaining()) throw Malformed("a vector longer than its message");
    v.clear();
    v.resize(size_t(n));
    for (T &x : v) Get(r, x);
}
template <typename T, size_t N>
void Put(Writer &w, const std::array<T, N> &a) {
    for (const T &x : a) Put(w, x);
}
template <typename T, size_t N>
void Get(Reader &r, std::array<T, N> &a) {
    for (T &x : a) Get(r, x);
}
template <typename A, typename B>
void Put(Writer &w, const std::pair<A, B> &p) {
    Put(w, p.first), Put(w, p.second);
}
template <typename A, typename B>
void Get(Reader &r, std::pair<A, B> &p) {
    Get(r, p.first), Get(r, p.second);
}

// ---------------------------------------------------------------------------
// Replies

// A reply starts with one of these bytes. Ok and Threw come from the code
// under test (in the worker, or in the judge's speculative runs, below); the
// others are the judge's verdicts on a worker that did not answer.
enum class Status : uint8_t {
    Ok = 0,
    Threw = 1,
    Crashed = 2,
    TimedOut = 3,
    OutOfMemory = 4,
    BadReply = 5,
};

// The kind of exception thrown, so that the judge can throw the same
// standard type (a test may expect std::invalid_argument).
enum class Thrown : uint8_t {
    InvalidArgument,
    OutOfRange,
    LogicError,
    RuntimeError,
    BadAlloc,
    OtherStd,
    NotStd,
};

// Runs f, which writes a result into w, and turns what it throws into a
// Threw reply.
template <typename F>
std::string Reply(F &&f) {
    Writer w;
    Put(w, uint8_t(Status::Ok));
    auto threw = [&](Thrown kind, const char *what) {
        w.bytes.clear();
        Put(w, uint8_t(Status::Threw));
        Put(w, uint8_t(kind));
        Put(w, std::string(what));
    };
    try {
        f(w);
    } catch (const std::invalid_argument &e) {
        threw(Thrown::InvalidArgument, e.what());
    } catch (const std::out_of_range &e) {
        threw(Thrown::OutOfRange, e.what());
    } catch (const std::logic_error &e) {
        threw(Thrown::LogicError, e.what());
    } catch (const std::runtime_error &e) {
        threw(Thrown::RuntimeError, e.what());
    } catch (const std::bad_alloc &e) {
        threw(Thrown::BadAlloc, e.what());
    } catch (const std::exception &e) {
        threw(Thrown::OtherStd, e.what());
    } catch (...) {
        threw(Thrown::NotStd, "an exception that is not a std::exception");
    }
    return w.bytes;
}

// ---------------------------------------------------------------------------
// Objects that outlive a call

// A call may keep an object (a BVH it built) for later calls of the same
// test: Keep() stores it and returns a Handle, which the call returns, and
// later calls pass the handle to Find(). In `make test` the handle holds the
// object; across the sandbox it is the id of the call that made it, and the
// process that ran that call (the worker, or the judge speculating) holds
// the object until the test ends.
struct Handle {
    uint64_t id = 0;
    std::shared_ptr<void> local;
    LRT_FIELDS(id)
};
struct Store {
    uint64_t currentCall = 0;    // the id of the call being served
    std::vector<std::pair<uint64_t, std::shared_ptr<void>>> objects;
};
inline Store &TheStore() {
    static Store store;
    return store;
}
inline Handle Keep(std::shared_ptr<void> object) {
    Handle h;
#if defined(LRT_JUDGE) || defined(LRT_WORKER)
    Store &s = TheStore();
    h.id = s.currentCall;
    s.objects.emplace_back(h.id, std::move(object));
#else
    h.local = std::move(object);
#endif
    return h;
}
#ifdef LRT_WORKER
// Files that a call gives the code it calls, by path, in memory: the worker
// may open no file (its system-call filter, tests/calls/wall.cpp), so its
// link routes fopen() to these first (worker.cpp, -Wl,--wrap=fopen).
inline std::map<std::string, std::string> &MemoryFiles() {
    static std::map<std::string, std::string> files;
    return files;
}
#endif
template <typename T>
T &Find(const Handle &h) {
    void *found = h.local.get();
    for (const auto &entry : TheStore().objects)
        if (!found && entry.first == h.id) found = entry.second.get();
    if (!found) throw std::invalid_argument("no object has this handle");
    return *static_cast<T *>(found);
}

// ---------------------------------------------------------------------------
// Calls

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

// The seed of a test's random cases: `seed` in `make test`, mixed with the
// grader's secret in the judge, so that graded random cases are new each time.
#ifdef LRT_JUDGE
uint64_t Seed(uint64_t seed);
#else
inline uint64_t Seed(uint64_t seed) { return seed; }
#endif

// How many random cases a test draws: `local` in `make test`, `graded` in the
// judge, where every call crosses to the worker and back (and the student's
// code runs unoptimized).
inline int Cases(int local, int graded) {
#ifdef LRT_JUDGE
    (void)local;
    return graded;
#else
    (void)graded;
    return local;
#endif
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
void RunRounds(void (*body)());
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

// A test of a graded exercise. In the judge its body may run several times
// (see judge.cpp); it must not depend on state left by an earlier run.
#ifdef LRT_JUDGE
#define EXERCISE_TEST(Suite, Name)                                  \
    static void Suite##_##Name##_Body();                            \
    TEST(Suite, Name) { ::lrt::calls::RunRounds(&Suite##_##Name##_Body); } \
    static void Suite##_##Name##_Body()
#else
#define EXERCISE_TEST(Suite, Name)                                  \
    static void Suite##_##Name##_Body();                            \
    TEST(Suite, Name) {                                             \
        try {                                                       \
            Suite##_##Name##_Body();                                \
        } catch (const ::lrt::calls::Later &later) {                \
            GTEST_SKIP() << later.message;                          \
        } catch (const std::logic_error &e) {                       \
            if (!::lrt::calls::IsLater(e)) throw;                   \
            GTEST_SKIP() << e.what();                               \
        }                                                           \
    }                                                               \
    static void Suite##_##Name##_Body()
#endif

#endif  // LRT_TESTS_CALLS_CORE_H
