// The worker: the student's code behind one chapter's exercise calls. The
// grader builds it with LRT_WORKER and LRT_CALLS_HEADER naming the chapter's
// tests/chNN/exercise_calls.h, links it with the student's code, and runs it
// in a sandbox; the judge (judge.cpp) sends it requests on file descriptor 3
// and reads the replies on 4. Each request is a call (a name and arguments);
// the worker answers it with what the code returns or throws, and knows
// nothing of the test that asked. A request with id 0 ends a test: the
// objects that calls kept are dropped.
//
// Frames, both ways, as framing.h writes and reads them. What the student's
// code prints goes to the worker's standard output and error, which the
// judge sends to a log.

#include "calls/framing.h"
#include "calls/memory_files.h"
#include "calls/reply.h"
#include "calls/rpc.h"

#include LRT_CALLS_HEADER

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

namespace {

// Requests are read in large blocks, one system call per block; each reply
// is written as soon as it is ready. The judge's time limit is per call: it
// times the worker from its last reply, so replies held back until a whole
// block (a few hundred calls) was answered made honest code of some tens of
// milliseconds a call look like a call that never ends.
class Channel {
  public:
    // The next request, or false at the end of the input.
    bool Next(uint64_t *id, std::string *message) {
        for (;;) {
            uint32_t n;
            if (in.NextLength(&n) && lrt::calls::FrameInbox::TooShort(n)) return false;
            if (in.Take(id, message)) return true;
            in.Compact();
            char buf[1 << 16];
            ssize_t r = read(3, buf, sizeof(buf));
            if (r <= 0) return false;
            in.Append(buf, size_t(r));
        }
    }
    // Writes one reply; false if the judge is gone.
    bool Send(uint64_t id, const std::string &reply) {
        std::string frame;
        lrt::calls::AppendFrame(&frame, id, reply);
        const char *p = frame.data();
        size_t n = frame.size();
        while (n > 0) {
            ssize_t r = write(4, p, n);
            if (r <= 0) return false;
            p += r;
            n -= size_t(r);
        }
        return true;
    }

  private:
    lrt::calls::FrameInbox in;
};

std::string Serve(const std::string &message) {
    using namespace lrt::calls;
    Reader r(message);
    std::string name;
    try {
        Get(r, name);
    } catch (const Malformed &) {
        return Reply([](Writer &) { throw Malformed("a request without a name"); });
    }
    for (const Operation &op : Operations())
        if (name == op.name) {
            try {
                return op.serve(r);
            } catch (const Malformed &e) {
                return Reply([&](Writer &) { throw e; });
            }
        }
    return Reply([&](Writer &) {
        throw std::invalid_argument("the worker has no call named " + name);
    });
}

// fopen() of the worker's objects, which its link routes here
// (-Wl,--wrap=fopen, tools/grading/build.py): a path that a call gave in memory
// (calls::MemoryFiles()) opens as a read-only stream of those bytes; any
// other goes to the C library's fopen, which the system-call filter lets
// open nothing.
struct MemoryFile {
    std::string bytes;
    size_t at = 0;
};

ssize_t ReadMemory(void *cookie, char *buffer, size_t size) {
    MemoryFile &f = *static_cast<MemoryFile *>(cookie);
    size_t n = std::min(size, f.bytes.size() - f.at);
    std::memcpy(buffer, f.bytes.data() + f.at, n);
    f.at += n;
    return ssize_t(n);
}

int CloseMemory(void *cookie) {
    delete static_cast<MemoryFile *>(cookie);
    return 0;
}

}  // namespace

extern "C" std::FILE *__real_fopen(const char *path, const char *mode);
extern "C" std::FILE *__wrap_fopen(const char *path, const char *mode) {
    const auto &files = lrt::calls::MemoryFiles();
    auto found = files.find(path);
    if (found == files.end() || mode[0] != 'r' || std::strchr(mode, '+'))
        return __real_fopen(path, mode);
    cookie_io_functions_t io = {ReadMemory, nullptr, nullptr, CloseMemory};
    return fopencookie(new MemoryFile{found->second}, "r", io);
}

int main() {
    Channel channel;
    uint64_t id;
    std::string message;
    while (channel.Next(&id, &message)) {
        bool sent;
        if (id == 0) {
            lrt::calls::TheStore().objects.clear();
            sent = channel.Send(0, "");
        } else {
            lrt::calls::TheStore().currentCall = id;
            sent = channel.Send(id, Serve(message));
        }
        if (!sent) break;
    }
    return 0;
}
