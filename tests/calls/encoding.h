// Exercise calls, the bytes: how arguments and results cross between the
// judge and the worker (docs/grading.md, "The trust boundary"). Arithmetic
// values bit for bit (NaNs and signed zeros included), strings, vectors,
// arrays, pairs, and structs that list their members with LRT_FIELDS(...);
// calls.h adds the library's geometry, a chapter's exercise_calls.h its own
// values. A Reader refuses (throws Malformed) what does not decode, since the
// worker's bytes come from the student's code.
//
// Included by rpc.h (and so by every build of the calls: the book's tests,
// the judge, the worker) and by calls.h. It needs nothing of the library.

#ifndef LRT_TESTS_CALLS_ENCODING_H
#define LRT_TESTS_CALLS_ENCODING_H

#include <array>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace lrt {
namespace calls {

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

}  // namespace calls
}  // namespace lrt

#endif  // LRT_TESTS_CALLS_ENCODING_H
