// Exercise calls, the objects that outlive a call (a BVH that later calls
// of the same test trace rays through).
//
// Included by rpc.h; used by a chapter's exercise_calls.h (Keep, Find), by
// worker.cpp and judge.cpp (TheStore: the current call, the end of a test).

#ifndef LRT_TESTS_CALLS_KEPT_H
#define LRT_TESTS_CALLS_KEPT_H

#include "calls/encoding.h"

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

namespace lrt {
namespace calls {

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
template <typename T>
T &Find(const Handle &h) {
    void *found = h.local.get();
    for (const auto &entry : TheStore().objects)
        if (!found && entry.first == h.id) found = entry.second.get();
    if (!found) throw std::invalid_argument("no object has this handle");
    return *static_cast<T *>(found);
}

}  // namespace calls
}  // namespace lrt

#endif  // LRT_TESTS_CALLS_KEPT_H
