// Exercise calls, the frames on the pipes between the judge and the worker:
// each request and each reply is a 4-byte length n, then n bytes: the
// call's 8-byte id and its message (rpc.h and reply.h encode the message).
// Both ends are the same machine, so the numbers are in its own byte order.
// An id of 0 ends a test (worker.cpp).
//
// Included by worker.cpp and judge.cpp, which both write frames with
// AppendFrame and take them from what they read with a FrameInbox. What each
// end refuses is its own: the judge limits what a worker may send
// (judge.cpp, kMaxFrame), the worker stops at a frame that is not one.

#ifndef LRT_TESTS_CALLS_FRAMING_H
#define LRT_TESTS_CALLS_FRAMING_H

#include <cstdint>
#include <cstring>
#include <string>

namespace lrt {
namespace calls {

const size_t kFrameLengthBytes = 4;
const uint32_t kFrameIdBytes = 8;

// Appends the frame of a message to `out`, for one write of many frames.
inline void AppendFrame(std::string *out, uint64_t id, const std::string &message) {
    uint32_t n = uint32_t(message.size() + kFrameIdBytes);
    out->append(reinterpret_cast<const char *>(&n), kFrameLengthBytes);
    out->append(reinterpret_cast<const char *>(&id), kFrameIdBytes);
    *out += message;
}

// Frames as they arrive: what is read is appended, whole frames are taken
// from the front. Taken bytes are dropped by Compact(), between reads, so
// that a large read of many frames is not copied once per frame.
class FrameInbox {
  public:
    void Append(const char *bytes, size_t n) { inbox.append(bytes, n); }

    // The length of the next frame (its id and message), once its first
    // kFrameLengthBytes have come.
    bool NextLength(uint32_t *n) const {
        if (inbox.size() - taken < kFrameLengthBytes) return false;
        std::memcpy(n, inbox.data() + taken, kFrameLengthBytes);
        return true;
    }

    // A length too short to hold an id: the stream is not frames.
    static bool TooShort(uint32_t n) { return n < kFrameIdBytes; }

    // Takes the next frame if all of it has come (its length not TooShort).
    bool Take(uint64_t *id, std::string *message) {
        uint32_t n;
        if (!NextLength(&n) || inbox.size() - taken < kFrameLengthBytes + size_t(n))
            return false;
        std::memcpy(id, inbox.data() + taken + kFrameLengthBytes, kFrameIdBytes);
        message->assign(inbox, taken + kFrameLengthBytes + kFrameIdBytes,
                        n - kFrameIdBytes);
        taken += kFrameLengthBytes + size_t(n);
        return true;
    }

    void Compact() {
        inbox.erase(0, taken);
        taken = 0;
    }
    void Clear() {
        inbox.clear();
        taken = 0;
    }

  private:
    std::string inbox;   // bytes read
    size_t taken = 0;    // of which frames already taken
};

}  // namespace calls
}  // namespace lrt

#endif  // LRT_TESTS_CALLS_FRAMING_H
