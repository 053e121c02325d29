// The judge: one chapter's exercise tests, compiled with LRT_JUDGE and linked
// with the book's code, whose exercise calls (calls.h) are answered by a
// worker process that runs the student's code in a sandbox. The grader
// (tools/grading/grade.py) starts it as
//
//   judge --lrt-worker=FILE --lrt-secret-file=FILE --lrt-tests-file=FILE
//         --lrt-results=FILE [--lrt-call-timeout=S] [--lrt-worker-log=FILE]
//
// The worker's FILE lists its command line, one argument a line (the sandbox,
// its limits and the worker binary); the secret's FILE holds the grading's
// secret (a decimal number), and the tests' FILE the tests to run, one
// Suite.Name a line; the results FILE gets a record per test as it ends, a
// line of JSON that says the test's verdict and what each failure is
// (ResultLines), from which the grader decides what a student sees. The
// judge never runs the student's code: it decides every verdict from the
// worker's answers, and the worker never learns which test asked.
//
// The secret and the tests come in files, which the grader keeps where only
// its own user can read them, and never on the command line: any process of
// the machine may read another's command line (/proc/PID/cmdline), a
// student's worker too where the sandbox has no namespaces of its own. A
// worker that knew the secret could tell the tests apart by their order;
// one that read the tests' names would know which it answers. So the judge
// also sets GoogleTest's filter, shuffle and seed itself (main), and starts
// each worker with an environment of its own (Worker::Start).
//
// Rounds. A test's body is written as straight-line code that calls
// lrt::ex::Name(...) and checks each result. Sending every call to the worker
// on its own would cost a round trip per call, which on a loaded two-core
// machine is tens of microseconds (some tests make a million calls). So the
// body runs in rounds: a call whose worker reply is not known yet gets a
// speculative reply from the book's code, so the body can go on, and is sent
// with the others in one batch at the end of the round. Where the worker's
// replies differ from the speculative ones, the body runs again with them, and
// what it asks that it did not ask before (a wrong answer changed its path)
// goes in the next batch. Then the body runs once more, as a plain GoogleTest
// body, with the worker's replies only (a call still unforeseen is asked on
// the spot): that run decides the test. The failures of the speculative
// rounds are intercepted, never reported; the book's code only ever steers a
// run whose failures are thrown away, and never answers for the student.

#include "calls/exercise_test.h"
#include "calls/framing.h"
#include "calls/reply.h"
#include "calls/rpc.h"

#include <gtest/gtest-spi.h>

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <vector>

namespace lrt {
namespace calls {

namespace {

// Aborts the body of a test after a worker failure (recorded as a failure
// first); not a std::exception, so that the body's own catch clauses for
// standard exceptions do not swallow it.
struct Abort {};

// What the judge accepts from a worker, which runs the student's code and
// may send anything. Measured on the book's code (chapters 3 and 6, hidden
// tests too): the largest reply is 0.93 MB (a BVH's nodes, chapter 6), the
// replies of one exercise's tests 11 MB in all. A test makes up to a few
// million calls, and code that throws in every one answers each with its
// message: the student edition's stubs (about 150 bytes) passed 256 MB in one
// test of chapter 5 for some seeds. So only what a reply holds beyond its
// first kFreeReplyBytes counts towards kMaxTestReplies: honest answers and
// short messages never reach it, and a worker that pads every answer to
// inflate the judge is stopped after 256 MB more than that. A frame larger
// than kMaxFrame, or a test whose counted replies pass kMaxTestReplies, is a
// failure of the call it answers, not a larger judge. What the student's
// code threw is shown cut to kMaxMessage bytes.
const uint32_t kMaxFrame = 4u << 20;
const size_t kFreeReplyBytes = 256;
const size_t kMaxTestReplies = 256u << 20;
const size_t kMaxMessage = 4096;
const int kMaxStarts = 40;               // worker processes per judge run
// A worker's exit status when the kernel refused its system-call filter: it
// never runs the student's code then (tests/calls/wall.cpp).
const int kWallRefused = 121;

struct Config {
    std::vector<std::string> workerArgv;
    std::string path;   // the judge's PATH, the one variable a worker gets
    std::string workerLog = "/dev/null";
    double callTimeout = 10;
    uint64_t secret = 0;
} config;

double Now() {
    timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

// What went wrong with a call, in words of the judge's own: a failure that a
// worker caused reads "during Call: KIND: DETAIL" on the judge's output.
// DETAIL (a signal, an exit status, a size, a message) the code under test
// can choose; the record of the failure (Judged) keeps KIND apart, as a
// fixed word (FailureWord), so that the grader can show a hidden test's
// failure without DETAIL (tools/grading/feedback.py).
const char *Kind(Status s) {
    switch (s) {
    case Status::Crashed: return "the code crashed";
    case Status::TimedOut: return "the code took too long";
    case Status::OutOfMemory: return "the code ran out of memory";
    default: return "the answer was refused";
    }
}

// A test's status when a worker failed during one of its calls.
const char *StatusWord(Status s) {
    switch (s) {
    case Status::Crashed: return "CRASH";
    case Status::TimedOut: return "TIMEOUT";
    case Status::OutOfMemory: return "OOM";
    default: return "FAIL";
    }
}

const char *FailureWord(Status s) {
    switch (s) {
    case Status::Crashed: return "crashed";
    case Status::TimedOut: return "timeout";
    case Status::OutOfMemory: return "oom";
    default: return "refused";
    }
}

std::string StatusReply(Status s, const std::string &what) {
    Writer w;
    Put(w, uint8_t(s));
    Put(w, what);
    return w.bytes;
}

std::string SignalName(int sig) {
    switch (sig) {
    case SIGSEGV: return "SIGSEGV";
    case SIGABRT: return "SIGABRT";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGBUS: return "SIGBUS";
    case SIGKILL: return "SIGKILL";
    case SIGXCPU: return "SIGXCPU";
    case SIGXFSZ: return "SIGXFSZ";
    case SIGTERM: return "SIGTERM";
    case SIGPIPE: return "SIGPIPE";
    case SIGSYS: return "SIGSYS";
    default: return "signal " + std::to_string(sig);
    }
}

// The processes that a worker leaves when it ends. The judge is a child
// subreaper (main): every process that loses its parent below the judge
// becomes the judge's child, not a child of the machine's first process.
// - With bubblewrap, the sandbox's own first process in its PID namespace
//   outlives the bwrap that the judge waits for by a moment. Left to the
//   machine's first process, which in a container may never reap, such
//   zombies counted against the sandbox user's process limit: after a few
//   dozen crashed workers (code that calls exit() in every call) no worker
//   could start, and the next exercises' tests failed with "the code exited
//   with status 1", the sandbox's failure counted as the student's crash.
// - Without namespaces (the fallback), nothing ends a worker's own children
//   with it: a setsid() daemon would live on as the sandbox's user, and
//   could kill the workers of the next exercise or the next grading.
// So whenever a worker has ended, every other child of the judge is killed
// and reaped, round after round, until none is left: killing one makes its
// own children the judge's.
std::vector<pid_t> Children() {
    std::vector<pid_t> found;
    DIR *proc = opendir("/proc");
    if (proc == nullptr) return found;
    std::string self = std::to_string(getpid());
    while (dirent *entry = readdir(proc)) {
        if (entry->d_name[0] < '1' || entry->d_name[0] > '9') continue;
        std::ifstream in(std::string("/proc/") + entry->d_name + "/stat");
        std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        // pid (comm) state ppid ...: comm may hold spaces and parentheses.
        size_t close = stat.rfind(')');
        if (close == std::string::npos) continue;
        std::istringstream fields(stat.substr(close + 1));
        std::string state, ppid;
        if (fields >> state >> ppid && ppid == self) found.push_back(std::atoi(entry->d_name));
    }
    closedir(proc);
    return found;
}

void EndChildren() {
    for (int round = 0; round < 1000; ++round) {
        std::vector<pid_t> children = Children();
        if (children.empty()) return;
        for (pid_t child : children) kill(child, SIGKILL);
        for (pid_t child : children)
            while (waitpid(child, nullptr, 0) < 0 && errno == EINTR) {
            }
    }
}

// The worker process: the sandbox with the student's code, spoken to through
// two pipes that the worker sees as file descriptors 3 (requests) and 4
// (replies); its standard output and error go to the worker log.
class Worker {
  public:
    ~Worker() { Stop(); }

    bool Running() const { return pid > 0; }

    // Starts a worker; false (with the reason) if none can be started.
    bool Start(std::string *why) {
        if (starts >= kMaxStarts) {
            *why = "the code crashed or hung too often (" +
                   std::to_string(kMaxStarts) + " worker processes)";
            return false;
        }
        if (config.workerArgv.empty()) {
            *why = "no worker command (--lrt-worker)";
            return false;
        }
        ++starts;
        int toWorker[2], fromWorker[2];
        if (pipe2(toWorker, O_CLOEXEC) != 0 || pipe2(fromWorker, O_CLOEXEC) != 0) {
            *why = "pipe() failed";
            return false;
        }
        std::vector<char *> argv;
        for (const std::string &a : config.workerArgv)
            argv.push_back(const_cast<char *>(a.c_str()));
        argv.push_back(nullptr);
        // Nothing of the judge's environment, which is the grader's and may
        // hold anything, but PATH, where the sandbox's commands are found.
        // bubblewrap clears the environment itself; without namespaces the
        // worker would otherwise get all of it.
        std::string pathVariable = "PATH=" + config.path;
        char *environment[] = {const_cast<char *>(pathVariable.c_str()), nullptr};
        int log = open(config.workerLog.c_str(),
                       O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0600);
        pid_t child = fork();
        if (child == 0) {
            // Only async-signal-safe calls between fork and exec.
            int null = open("/dev/null", O_RDONLY);
            if (null < 0 || dup2(null, 0) < 0) _exit(126);
            int out = log >= 0 ? log : null;
            if (dup2(out, 1) < 0 || dup2(out, 2) < 0) _exit(126);
            // Out of the way first, so that neither lands on the other's
            // number; dup2 clears close-on-exec on 3 and 4.
            int in = fcntl(toWorker[0], F_DUPFD_CLOEXEC, 10);
            int back = fcntl(fromWorker[1], F_DUPFD_CLOEXEC, 10);
            if (in < 0 || back < 0 || dup2(in, 3) < 0 || dup2(back, 4) < 0)
                _exit(126);
            for (int fd = 5; fd < 1024; ++fd) close(fd);
            execvpe(argv[0], argv.data(), environment);
            _exit(127);
        }
        if (log >= 0) close(log);
        close(toWorker[0]);
        close(fromWorker[1]);
        if (child < 0) {
            close(toWorker[1]);
            close(fromWorker[0]);
            *why = "fork() failed";
            return false;
        }
        pid = child;
        to = toWorker[1];
        from = fromWorker[0];
        fcntl(to, F_SETFL, O_NONBLOCK);
        fcntl(from, F_SETFL, O_NONBLOCK);
        inbox.Clear();
        return true;
    }

    // Stops the worker (the sandbox ends with it) and says how it ended:
    // at once, or, for a worker that closed its end (it is exiting, or it
    // stopped answering), after a moment's grace.
    std::string Stop(bool kill = true) {
        if (pid <= 0) return "";
        close(to);
        close(from);
        int status = 0;
        bool ended = false;
        for (int waited = 0; !kill && !ended && waited < 200; ++waited) {
            ended = waitpid(pid, &status, WNOHANG) == pid;
            if (!ended) usleep(10000);
        }
        if (!ended) {
            ::kill(pid, SIGKILL);
            while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
            }
        }
        pid = -1;
        EndChildren();
        if (WIFSIGNALED(status)) return "killed by " + SignalName(WTERMSIG(status));
        if (WIFEXITED(status)) {
            int code = WEXITSTATUS(status);
            if (code == kWallRefused)
                return "exited with status " + std::to_string(code) + " (or could not "
                       "start: the kernel refused the worker's system-call filter)";
            // The sandbox reports a signal that ended the program as 128 + n.
            if (code > 128 && code < 128 + 65)
                return "killed by " + SignalName(code - 128);
            return "exited with status " + std::to_string(code);
        }
        return "ended";
    }

    // Sends one test's requests (id, bytes) and collects one reply per
    // request, in order. A worker that crashes, hangs or answers out of turn
    // gets a failure reply for the request it was on, and is stopped; the
    // test's later requests are not asked (its verdict run stops at that
    // failure), and the next exchange starts a new worker.
    std::vector<std::string> Exchange(
        const std::vector<std::pair<uint64_t, std::string>> &requests) {
        std::vector<std::string> replies;
        std::string why;
        if (!Running() && !Start(&why)) {
            while (replies.size() < requests.size())
                replies.push_back(StatusReply(Status::Crashed, why));
            return replies;
        }
        std::string out;
        for (const auto &request : requests) AppendFrame(&out, request.first, request.second);
        Pump(out, requests, &replies);
        if (replies.size() < requests.size()) {
            // The last reply says what went wrong; the rest share it.
            Reader r(replies.back());
            uint8_t status;
            std::string what;
            Get(r, status);
            Get(r, what);
            while (replies.size() < requests.size())
                replies.push_back(StatusReply(
                    Status(status), "not asked, after an earlier call: " + what));
        }
        return replies;
    }

    // Ends the test: the worker drops the objects it kept.
    void Reset() {
        received = 0;
        if (!Running()) return;
        std::vector<std::pair<uint64_t, std::string>> reset{{0, ""}};
        Exchange(reset);
    }

  private:
    // Writes `out` and reads replies until every request has one or the
    // worker fails (then it is stopped and the failure is the reply of the
    // request it was on).
    void Pump(const std::string &out,
              const std::vector<std::pair<uint64_t, std::string>> &requests,
              std::vector<std::string> *replies) {
        size_t written = 0;
        double last = Now();
        while (replies->size() < requests.size()) {
            pollfd fds[2] = {{from, POLLIN, 0}, {to, POLLOUT, 0}};
            int nfds = written < out.size() ? 2 : 1;
            double left = config.callTimeout - (Now() - last);
            int r = left > 0 ? poll(fds, nfds, int(left * 1000) + 1) : 0;
            if (r < 0 && errno == EINTR) continue;
            if (r <= 0 && Now() - last >= config.callTimeout) {
                Stop();
                replies->push_back(StatusReply(
                    Status::TimedOut, "no answer within the time limit of " +
                                          Seconds(config.callTimeout)));
                return;
            }
            if (nfds == 2 && (fds[1].revents & (POLLOUT | POLLERR | POLLHUP))) {
                ssize_t n = write(to, out.data() + written, out.size() - written);
                if (n > 0) written += size_t(n);
                if (n < 0 && errno != EAGAIN && errno != EINTR)
                    written = out.size();   // the worker is gone; read why
            }
            if (fds[0].revents & (POLLIN | POLLERR | POLLHUP)) {
                char buf[1 << 16];
                ssize_t n = read(from, buf, sizeof(buf));
                if (n > 0) {
                    inbox.Append(buf, size_t(n));
                    while (TakeReply(requests, replies, &last)) {
                    }
                    inbox.Compact();
                    if (!overLimit.empty()) {
                        Stop();
                        replies->push_back(StatusReply(Status::BadReply, overLimit));
                        overLimit.clear();
                        return;
                    }
                    if (failed) {
                        failed = false;
                        Stop();
                        replies->push_back(StatusReply(
                            Status::BadReply, "the answer was not in the "
                                              "format of the exercise calls"));
                        return;
                    }
                } else if (n == 0 || (errno != EAGAIN && errno != EINTR)) {
                    std::string how = Stop(false);
                    Status s = how.find("SIGXCPU") != std::string::npos
                                   ? Status::TimedOut
                                   : Status::Crashed;
                    replies->push_back(StatusReply(s, how));
                    return;
                }
            }
        }
    }

    // Moves one complete reply from the inbox to the replies.
    bool TakeReply(const std::vector<std::pair<uint64_t, std::string>> &requests,
                   std::vector<std::string> *replies, double *last) {
        uint32_t n;
        if (replies->size() >= requests.size() || !inbox.NextLength(&n)) return false;
        if (n > kMaxFrame) {
            overLimit = "the answer was larger than " + std::to_string(kMaxFrame >> 20) +
                        " MB (what the code returned or threw)";
            return false;
        }
        size_t counted = n > kFreeReplyBytes ? n - kFreeReplyBytes : 0;
        if (received + counted > kMaxTestReplies) {
            overLimit = "the answers of this test came to more than " +
                        std::to_string(kMaxTestReplies >> 20) + " MB in all";
            return false;
        }
        if (FrameInbox::TooShort(n)) {
            failed = true;
            return false;
        }
        uint64_t id;
        std::string reply;
        if (!inbox.Take(&id, &reply)) return false;
        if (id != requests[replies->size()].first) {
            failed = true;
            return false;
        }
        replies->push_back(std::move(reply));
        received += counted;
        *last = Now();
        return true;
    }

    static std::string Seconds(double s) {
        char buf[32];
        std::snprintf(buf, sizeof(buf), "%g s", s);
        return buf;
    }

    pid_t pid = -1;
    int to = -1, from = -1;
    int starts = 0;
    bool failed = false;
    std::string overLimit;   // why the worker's last frame was refused
    size_t received = 0;     // bytes of replies in this test that count
    FrameInbox inbox;     // replies read from the worker
};

Worker *worker = nullptr;

// One test's calls, across its rounds.
struct Slot {
    uint64_t id;
    std::string request;
    std::string reply;
};
struct Session {
    std::vector<Slot> slots;      // every call the body made, in order
    size_t next = 0;              // the call the body makes next
    std::vector<size_t> pending;  // slots answered speculatively this round
    bool verdict = false;         // the run whose failures count
    std::exception_ptr thrown;    // the last exception a call's reply threw
    std::string thrownBy;         // and that call
};
Session *session = nullptr;
uint64_t lastId = 0;

// What the judge knows of a failure that it reported itself, in the
// verdict run: a worker that failed during a call (kind "worker": failure
// one of FailureWord's words, detail what the judge saw), or an exception
// that left the body (kind "threw": the call whose reply threw it, if it
// is that exception, and its message). Every other failure of a test is one
// of the test's own checks. The grader decides the statuses and what a
// student sees from these fields alone (ResultLines writes them), never
// from a failure's words, which hold what the student's code returned or
// threw: that code can write anything, but no field but detail and message.
struct Judged {
    std::string kind, call, failure, detail;
    bool described = true;   // threw: an exception with a message (what())
};
// The current test's: its failures that the judge reported, by their index
// among the test's parts, and the status of its first worker failure
// (CRASH, TIMEOUT, OOM, FAIL), which is the test's verdict if it failed.
struct TestRecord {
    std::map<int, Judged> judged;
    std::string worst;
} current;

// Keeps what the failure just reported is (the last part of the test).
void Keep(const Judged &what) {
    const ::testing::TestInfo *test = ::testing::UnitTest::GetInstance()->current_test_info();
    if (test != nullptr) current.judged[test->result()->total_part_count() - 1] = what;
}

// A worker's failure during `call`: reported, and kept in the verdict run
// (a speculative round's failures are intercepted, never part of the test).
void WorkerFailure(const char *call, Status s, const std::string &detail) {
    bool verdict = session && session->verdict;
    if (verdict && current.worst.empty()) current.worst = StatusWord(s);
    ADD_FAILURE() << "during " << call << ": " << Kind(s) << ": " << detail;
    if (verdict) Keep({"worker", call, FailureWord(s), detail});
}

// An exception that left the verdict run's body, reported as GoogleTest
// reports one (with its words, at no location) and kept: the call named
// only if it is the very exception that the call's reply threw.
void EscapedException(const Session &s) {
    Judged what{"threw", std::current_exception() == s.thrown ? s.thrownBy : "", "", ""};
    std::string text;
    try {
        throw;
    } catch (const std::exception &e) {
        what.detail = e.what();
        text = "C++ exception with description \"" + what.detail + "\" thrown in the test body.";
    } catch (...) {
        what.described = false;
        text = "Unknown C++ exception thrown in the test body.";
    }
    ::testing::internal::AssertHelper(::testing::TestPartResult::kFatalFailure, nullptr, -1,
                                      text.c_str()) = ::testing::Message();
    Keep(what);
}

// Standard output goes nowhere while it lives: what a body prints in its
// speculative rounds would otherwise appear once per round.
class Quiet {
  public:
    Quiet() {
        std::cout.flush();
        std::fflush(stdout);
        saved = dup(1);
        int null = open("/dev/null", O_WRONLY);
        if (saved >= 0 && null >= 0) dup2(null, 1);
        if (null >= 0) close(null);
    }
    ~Quiet() {
        std::cout.flush();
        std::fflush(stdout);
        if (saved >= 0) {
            dup2(saved, 1);
            close(saved);
        }
    }

  private:
    int saved;
};

}  // namespace

uint64_t Seed(uint64_t seed) {
    // splitmix64 of the two: a different, unpredictable stream per grading.
    uint64_t z = seed + config.secret * 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

std::string Answer(const std::string &request,
                   const std::function<std::string()> &speculate) {
    if (!session) {
        ADD_FAILURE() << "an exercise call outside an EXERCISE_TEST";
        throw Abort();
    }
    Session &s = *session;
    size_t i = s.next++;
    if (i < s.slots.size()) {
        if (s.slots[i].request == request) return s.slots[i].reply;
        s.slots.resize(i);   // the body took another path: ask again from here
    }
    Slot slot{++lastId, request, ""};
    if (s.verdict) {
        // A call the speculative rounds did not foresee: ask the worker now.
        slot.reply = worker->Exchange({{slot.id, request}})[0];
    } else {
        TheStore().currentCall = slot.id;
        slot.reply = speculate();
        s.pending.push_back(i);
    }
    s.slots.push_back(slot);
    return s.slots.back().reply;
}

void Unpack(const std::string &reply, const char *name, Reader *r) {
    uint8_t status;
    Get(*r, status);
    if (Status(status) == Status::Ok) return;
    if (Status(status) == Status::Threw) {
        uint8_t kind;
        std::string what;
        Get(*r, kind);
        Get(*r, what);
        if (what.size() > kMaxMessage)
            what = what.substr(0, kMaxMessage) + " [... " +
                   std::to_string(what.size() - kMaxMessage) + " more bytes]";
        if (Thrown(kind) == Thrown::BadAlloc) {
            WorkerFailure(name, Status::OutOfMemory, "it threw std::bad_alloc");
            throw Abort();
        }
        std::exception_ptr thrown;
        switch (Thrown(kind)) {
        case Thrown::InvalidArgument:
            thrown = std::make_exception_ptr(std::invalid_argument(what));
            break;
        case Thrown::OutOfRange: thrown = std::make_exception_ptr(std::out_of_range(what)); break;
        case Thrown::LogicError: thrown = std::make_exception_ptr(std::logic_error(what)); break;
        default: thrown = std::make_exception_ptr(std::runtime_error(what));
        }
        // Kept, to tell this exception from any other that leaves the body
        // (EscapedException): by identity, never by its words.
        if (session) {
            session->thrown = thrown;
            session->thrownBy = name;
        }
        std::rethrow_exception(thrown);
    }
    std::string what;
    try {
        Get(*r, what);
    } catch (const Malformed &) {
        what = "no reply";
    }
    Status s = Status(status);
    if (s != Status::Crashed && s != Status::TimedOut && s != Status::BadReply &&
        s != Status::OutOfMemory)
        what = "an unknown reply";
    WorkerFailure(name, s, what);
    (void)reply;
    throw Abort();
}

void RunRounds(void (*body)()) {
    Session s;
    session = &s;
    struct Cleanup {
        ~Cleanup() {
            session = nullptr;
            TheStore().objects.clear();
            worker->Reset();
        }
    } cleanup;
    // Speculative rounds: failures intercepted, calls collected and sent.
    const int kMaxRounds = 16;
    for (int round = 0; round < kMaxRounds; ++round) {
        s.next = 0;
        s.pending.clear();
        ::testing::TestPartResultArray ignored;
        Quiet quiet;
        {
            ::testing::ScopedFakeTestPartResultReporter intercept(
                ::testing::ScopedFakeTestPartResultReporter::
                    INTERCEPT_ONLY_CURRENT_THREAD,
                &ignored);
            try {
                body();
            } catch (...) {
            }
        }
        if (s.pending.empty()) break;
        std::vector<std::pair<uint64_t, std::string>> requests;
        for (size_t i : s.pending)
            requests.emplace_back(s.slots[i].id, s.slots[i].request);
        std::vector<std::string> replies = worker->Exchange(requests);
        // Where the worker answered exactly as the book's code did, the body
        // takes the same path again and asks nothing new: no further round.
        bool asSpeculated = true;
        for (size_t k = 0; k < s.pending.size(); ++k) {
            asSpeculated = asSpeculated && s.slots[s.pending[k]].reply == replies[k];
            s.slots[s.pending[k]].reply = replies[k];
        }
        if (asSpeculated) break;
    }
    // The verdict: the body once more, as a plain GoogleTest body, every
    // reply the worker's (a call not seen before is asked for on the spot).
    s.next = 0;
    s.verdict = true;
    try {
        body();
    } catch (const Abort &) {
    } catch (...) {
        // What the code threw and the body did not catch, with the call that
        // threw it: the grader names the call where it must not show the
        // message (a hidden test).
        EscapedException(s);
    }
}

}  // namespace calls
}  // namespace lrt

namespace {

bool StartsWith(const std::string &s, const std::string &prefix) {
    return s.compare(0, prefix.size(), prefix) == 0;
}

#ifdef GTEST_FLAG_SET
#define LRT_GTEST_SET(name, value) GTEST_FLAG_SET(name, value)
#else
#define LRT_GTEST_SET(name, value) (void)(::testing::GTEST_FLAG(name) = (value))
#endif

// The grading's secret, a decimal number alone in a file (a final newline
// allowed).
bool ReadSecret(const std::string &path, uint64_t *secret) {
    std::ifstream in(path);
    std::string text, rest;
    if (!(in >> text) || in >> rest || text.size() > 20 ||
        text.find_first_not_of("0123456789") != std::string::npos)
        return false;
    errno = 0;
    *secret = std::strtoull(text.c_str(), nullptr, 10);
    return errno == 0;
}

// The length of the well-formed UTF-8 sequence at s[i] that encodes a
// character above U+007F (the shortest form, no surrogate, at most U+10FFFF),
// or 0 if none starts there.
size_t Utf8Sequence(const std::string &s, size_t i) {
    unsigned char c = s[i];
    size_t n = c >= 0xf0 ? 4 : c >= 0xe0 ? 3 : c >= 0xc2 ? 2 : 0;
    if (n == 0 || c > 0xf4 || i + n > s.size()) return 0;
    for (size_t k = 1; k < n; ++k)
        if ((static_cast<unsigned char>(s[i + k]) & 0xc0) != 0x80) return 0;
    unsigned char d = s[i + 1];
    if ((c == 0xe0 && d < 0xa0) || (c == 0xed && d >= 0xa0) ||
        (c == 0xf0 && d < 0x90) || (c == 0xf4 && d >= 0x90))
        return 0;
    return n;
}

// A JSON string of any bytes: what a student's code threw may be anything,
// and one line that is not JSON would lose its test's verdict, so a byte
// that is not part of well-formed UTF-8 becomes U+FFFD.
std::string JsonString(const std::string &s) {
    std::string out = "\"";
    for (size_t i = 0; i < s.size(); ++i) {
        unsigned char c = s[i];
        if (c == '"' || c == '\\') {
            out += '\\';
            out += char(c);
        } else if (c < 0x20 || c == 0x7f) {
            char buf[8];
            std::snprintf(buf, sizeof(buf), "\\u%04x", c);
            out += buf;
        } else if (c < 0x80) {
            out += char(c);
        } else if (size_t n = Utf8Sequence(s, i)) {
            out.append(s, i, n);
            i += n - 1;
        } else {
            out += "\\ufffd";
        }
    }
    return out + "\"";
}

// The failures of one test that its line keeps, and their length: a check
// may print a value of the student's code (a long string), and the verdicts
// and the feedback stay small.
const int kMaxFailures = 20;
const size_t kMaxFailureText = 8192;

std::string Cut(const std::string &text) {
    if (text.size() <= kMaxFailureText) return text;
    return text.substr(0, kMaxFailureText) + " [... " +
           std::to_string(text.size() - kMaxFailureText) + " more bytes]";
}

// Writes a record per finished test to a file, a line of JSON, at once, so
// that what finished is known even if the judge is stopped later:
//   {"test": "Suite.Name", "verdict": "PASS", "failures": [...]}
// verdict: PASS, FAIL, or the status of the verdict run's first worker
// failure (CRASH, TIMEOUT, OOM); failures, each one of
//   {"kind": "check", "where": "tests/ch05/x.cpp:12", "text": "..."}
//   {"kind": "worker", "call": "Name", "failure": "crashed", "detail": "..."}
//   {"kind": "threw", "call": "Name", "message": "..."}
// (failure: crashed, timeout, oom or refused; call "" if the exception came
// from no call's reply; message null if it had none). Only this process
// writes the file, and what the student's code chose is only ever a JSON
// string's value (detail, message, text): no output of a worker, no
// exception's words, no test's name can make a record or a field of one.
// The grader reads these with a schema (tools/grading/records.py).
class ResultLines : public ::testing::EmptyTestEventListener {
  public:
    explicit ResultLines(const std::string &path) : out(path, std::ios::app) {}
    bool ok() const { return bool(out); }
    void OnTestStart(const ::testing::TestInfo &) override {
        lrt::calls::current = lrt::calls::TestRecord();
    }
    void OnTestEnd(const ::testing::TestInfo &info) override {
        const ::testing::TestResult *r = info.result();
        const lrt::calls::TestRecord &record = lrt::calls::current;
        std::string verdict = r->Passed()              ? "PASS"
                              : record.worst.empty() ? "FAIL"
                                                     : record.worst;
        out << "{\"test\": "
            << JsonString(std::string(info.test_suite_name()) + "." + info.name())
            << ", \"verdict\": " << JsonString(verdict) << ", \"failures\": [";
        int shown = 0;
        for (int i = 0; i < r->total_part_count() && shown < kMaxFailures; ++i) {
            const ::testing::TestPartResult &part = r->GetTestPartResult(i);
            if (!part.failed()) continue;
            out << (shown++ ? ", " : "") << Failure(part, record.judged.find(i),
                                                    record.judged.end());
        }
        out << "]}\n";
        out.flush();
    }

  private:
    using Found = std::map<int, lrt::calls::Judged>::const_iterator;

    static std::string Failure(const ::testing::TestPartResult &part, Found judged,
                               Found none) {
        if (judged == none) {
            std::string where = part.file_name() ? part.file_name() : "";
            if (!where.empty() && part.line_number() >= 0)
                where += ":" + std::to_string(part.line_number());
            return "{\"kind\": \"check\", \"where\": " + JsonString(where) +
                   ", \"text\": " + JsonString(Cut(part.message())) + "}";
        }
        const lrt::calls::Judged &j = judged->second;
        if (j.kind == "worker")
            return "{\"kind\": \"worker\", \"call\": " + JsonString(j.call) +
                   ", \"failure\": " + JsonString(j.failure) +
                   ", \"detail\": " + JsonString(Cut(j.detail)) + "}";
        return "{\"kind\": \"threw\", \"call\": " + JsonString(j.call) + ", \"message\": " +
               (j.described ? JsonString(Cut(j.detail)) : std::string("null")) + "}";
    }

    std::ofstream out;
};

}  // namespace

int main(int argc, char **argv) {
    using lrt::calls::config;
    // The judge writes to pipes of workers that may have died.
    signal(SIGPIPE, SIG_IGN);
    // What the workers leave comes to the judge (EndChildren).
    prctl(PR_SET_CHILD_SUBREAPER, 1);
    const char *path = std::getenv("PATH");
    config.path = path && *path ? path : "/usr/bin:/bin";
    std::vector<char *> rest{argv[0]};
    std::string results, tests;
    bool haveTests = false;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (StartsWith(a, "--lrt-worker=")) {
            std::ifstream in(a.substr(13));
            if (!in) {
                std::cerr << "judge: cannot read " << a.substr(13) << "\n";
                return 2;
            }
            for (std::string line; std::getline(in, line);)
                config.workerArgv.push_back(line);
        } else if (StartsWith(a, "--lrt-secret-file=")) {
            if (!ReadSecret(a.substr(18), &config.secret)) {
                std::cerr << "judge: no secret (a decimal number) in " << a.substr(18)
                          << "\n";
                return 2;
            }
        } else if (StartsWith(a, "--lrt-tests-file=")) {
            std::ifstream in(a.substr(17));
            if (!in) {
                std::cerr << "judge: cannot read " << a.substr(17) << "\n";
                return 2;
            }
            for (std::string line; std::getline(in, line);)
                if (!line.empty()) tests += (tests.empty() ? "" : ":") + line;
            haveTests = true;
        } else if (StartsWith(a, "--lrt-secret=") || StartsWith(a, "--gtest_random_seed")) {
            std::cerr << "judge: the secret goes in a file (--lrt-secret-file), never on "
                         "a command line, which every process can read\n";
            return 2;
        } else if (StartsWith(a, "--lrt-call-timeout=")) {
            config.callTimeout = std::atof(a.c_str() + 19);
        } else if (StartsWith(a, "--lrt-worker-log=")) {
            config.workerLog = a.substr(17);
        } else if (StartsWith(a, "--lrt-results=")) {
            results = a.substr(14);
        } else {
            rest.push_back(argv[i]);
        }
    }
    int n = int(rest.size());
    ::testing::InitGoogleTest(&n, rest.data());
    // The tests run in an order that the secret shuffles (GoogleTest's seeds
    // go from 1 to 99999), set here rather than given as --gtest_shuffle
    // --gtest_random_seed=N, which would put the seed, and so part of the
    // secret, on the command line; and the tests to run likewise.
    LRT_GTEST_SET(shuffle, true);
    LRT_GTEST_SET(random_seed, int(config.secret % 99999 + 1));
    if (haveTests) LRT_GTEST_SET(filter, tests.empty() ? std::string("-*") : tests);
    if (!results.empty()) {
        auto *lines = new ResultLines(results);
        if (!lines->ok()) {
            std::cerr << "judge: cannot write " << results << "\n";
            return 2;
        }
        ::testing::UnitTest::GetInstance()->listeners().Append(lines);
    }
    lrt::calls::Worker w;
    lrt::calls::worker = &w;
    int status = RUN_ALL_TESTS();
    w.Stop();
    return status;
}
