// Exercise calls, the replies: the status byte a reply starts with, and
// Reply(), which runs a call and encodes what it returns or throws. The
// worker answers every request so; the judge reads these replies (Unpack)
// and writes its own for a worker that did not answer (a crash, a timeout).
//
// Included by rpc.h (a served call replies with Reply()), worker.cpp and
// judge.cpp.

#ifndef LRT_TESTS_CALLS_REPLY_H
#define LRT_TESTS_CALLS_REPLY_H

#include "calls/encoding.h"

#include <cstdint>
#include <new>
#include <stdexcept>
#include <string>

namespace lrt {
namespace calls {

// A reply starts with one of these bytes. Ok and Threw come from the code
// under test (in the worker, or in the judge's speculative runs, judge.cpp); the
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

}  // namespace calls
}  // namespace lrt

#endif  // LRT_TESTS_CALLS_REPLY_H
