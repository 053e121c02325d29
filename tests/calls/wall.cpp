// The worker's wall: a seccomp filter that the worker installs on itself
// before any of the student's code can run, so that whatever that code does,
// the only system calls that reach the kernel are those that answering
// exercise calls needs (docs/grading.md, "The sandbox").
//
// Why a filter, when bubblewrap already isolates the worker: where bubblewrap
// cannot make namespaces (a container's default seccomp profile, the
// autograder's container), the grader falls back to running the worker as an
// unused uid with limits and no namespaces. That worker sees the whole file
// system as that uid (the repository's chapters hold every exercise's
// solution), can open sockets, start programs, fork, and signal every process
// of its uid. With this filter it can do none of that, in either mode: it
// reads and writes the descriptors it was given, manages its own memory,
// signals itself (abort()), waits on futexes, reads clocks and random bytes,
// and exits. Every other call fails with EPERM: a student's debugging
// std::ofstream or std::thread then just fails (an error the student can
// see), instead of killing the worker. Calls of another ABI (32-bit x86
// through int 0x80, x32), which no honest code of the worker makes, kill it.
//
// Why at the entry point: the student's code can run before main (the
// initializer of an inline variable or a template's static member in a
// header, at static-initialization time), and a static glibc runs IFUNC
// resolvers and constructors before that. So the worker's ELF entry point is
// lrt_wall_entry below (`-Wl,-e,lrt_wall_entry`, tools/grading/build.py), in
// this translation unit, which holds no student code. It runs before the C
// library has set up anything (no TLS, no errno, no IFUNCs resolved), so it
// makes raw system calls and calls no library function, installs the filter,
// and only then jumps to the C library's own entry point, _start, with the
// registers the kernel gave. If the kernel refuses the filter, the worker
// writes why to its standard error (the worker log) and exits with
// LRT_WALL_REFUSED: it never runs without the filter. The judge names that
// status (tests/calls/judge.cpp).
//
// The allowlist was found by tracing static workers of the book's code and of
// stubs that throw, abort and print (strace -f), after the filter: glibc's
// start (arch_prctl for TLS, set_tid_address, set_robust_list, rseq, brk,
// mprotect of RELRO, getrandom for malloc), the calls loop (read on 3, write
// on 4), exceptions and allocation (mmap, munmap, brk), abort() (getpid,
// gettid, tgkill, rt_sigprocmask, rt_sigaction) and exit_group. Calls that
// glibc's start makes but can do without are denied: prlimit64 (it can set
// other processes' limits; glibc falls back to a default stack size) and
// readlink (of /proc/self/exe; it can read any link).

#if !defined(__x86_64__) || defined(__ILP32__)
#error "the worker's system-call filter (wall.cpp) is written for x86-64 Linux"
#endif

#include <asm/unistd.h>
#include <linux/audit.h>
#include <linux/errno.h>
#include <linux/filter.h>
#include <linux/prctl.h>
#include <linux/seccomp.h>

#include <stddef.h>

// The worker's exit status when the kernel refuses the filter.
#define LRT_WALL_REFUSED 121

namespace {

// The file descriptors the worker may read and write: 0 (/dev/null), 1 and 2
// (the worker log), 3 (requests) and 4 (replies). It cannot make others:
// open, socket, pipe and dup are denied.
const unsigned kLastFd = 4;

#define LRT_LOAD(offset) BPF_STMT(BPF_LD | BPF_W | BPF_ABS, (offset))
#define LRT_RETURN(action) BPF_STMT(BPF_RET | BPF_K, (action))
#define LRT_DENY LRT_RETURN(SECCOMP_RET_ERRNO | EPERM)
#define LRT_ALLOW(nr) BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, (nr), 0, 1), \
                      LRT_RETURN(SECCOMP_RET_ALLOW)

// The low 32 bits of argument 0 (little-endian): the kernel reads an int or
// unsigned int argument (a descriptor, a pid) from those bits alone.
const unsigned kArg0 = offsetof(struct seccomp_data, args[0]);

// The instruction whose constant is the worker's own pid, set at run time.
const unsigned kOwnPidAt = 18;

// The filter: the kernel runs it on every system call of the worker, and of
// nothing else (it is inherited by children, but the worker can make none).
// Not const: the pid is written into it before it is installed.
sock_filter filter[] = {
    /*  0 */ LRT_LOAD(offsetof(struct seccomp_data, arch)),
    /*  1 */ BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, AUDIT_ARCH_X86_64, 1, 0),
    /*  2 */ LRT_RETURN(SECCOMP_RET_KILL_PROCESS),
    /*  3 */ LRT_LOAD(offsetof(struct seccomp_data, nr)),
    /*  4 */ BPF_JUMP(BPF_JMP | BPF_JGE | BPF_K, __X32_SYSCALL_BIT, 0, 1),
    /*  5 */ LRT_RETURN(SECCOMP_RET_KILL_PROCESS),

    // Reads and writes, on the worker's own descriptors only.
    /*  6 */ BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, __NR_read, 3, 0),
    /*  7 */ BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, __NR_write, 2, 0),
    /*  8 */ BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, __NR_readv, 1, 0),
    /*  9 */ BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, __NR_writev, 0, 4),
    /* 10 */ LRT_LOAD(kArg0),
    /* 11 */ BPF_JUMP(BPF_JMP | BPF_JGT | BPF_K, kLastFd, 1, 0),
    /* 12 */ LRT_RETURN(SECCOMP_RET_ALLOW),
    /* 13 */ LRT_DENY,

    // Signals to itself alone: abort() raises SIGABRT with tgkill. kill(-1)
    // or kill(0), a process group, another pid: denied. With fork and clone
    // denied the worker has one thread, whose tid is its pid.
    /* 14 */ BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, __NR_kill, 2, 0),
    /* 15 */ BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, __NR_tkill, 1, 0),
    /* 16 */ BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, __NR_tgkill, 0, 4),
    /* 17 */ LRT_LOAD(kArg0),
    /* 18 */ BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, 0 /* the worker's pid */, 0, 1),
    /* 19 */ LRT_RETURN(SECCOMP_RET_ALLOW),
    /* 20 */ LRT_DENY,

    // Its own memory.
    LRT_ALLOW(__NR_mmap),
    LRT_ALLOW(__NR_munmap),
    LRT_ALLOW(__NR_mremap),
    LRT_ALLOW(__NR_mprotect),
    LRT_ALLOW(__NR_brk),
    LRT_ALLOW(__NR_madvise),
    // Its end.
    LRT_ALLOW(__NR_exit_group),
    LRT_ALLOW(__NR_exit),
    LRT_ALLOW(__NR_close),
    // Its signals (abort(), a handler of its own), its threads' futexes.
    LRT_ALLOW(__NR_rt_sigaction),
    LRT_ALLOW(__NR_rt_sigprocmask),
    LRT_ALLOW(__NR_rt_sigreturn),
    LRT_ALLOW(__NR_getpid),
    LRT_ALLOW(__NR_gettid),
    LRT_ALLOW(__NR_futex),
    // Clocks and waits (a wait counts against the call's time limit), and
    // the kernel's restart of a wait that a signal interrupted.
    LRT_ALLOW(__NR_clock_gettime),
    LRT_ALLOW(__NR_clock_getres),
    LRT_ALLOW(__NR_gettimeofday),
    LRT_ALLOW(__NR_time),
    LRT_ALLOW(__NR_nanosleep),
    LRT_ALLOW(__NR_clock_nanosleep),
    LRT_ALLOW(__NR_sched_yield),
    LRT_ALLOW(__NR_restart_syscall),
    LRT_ALLOW(__NR_getrandom),
    // glibc's start, after the filter: the thread pointer (TLS), its own
    // thread's bookkeeping.
    LRT_ALLOW(__NR_arch_prctl),
    LRT_ALLOW(__NR_set_tid_address),
    LRT_ALLOW(__NR_set_robust_list),
    LRT_ALLOW(__NR_rseq),

    // Everything else: open, openat, stat, socket, connect, fork, vfork,
    // clone, clone3, execve, ptrace, process_vm_readv, shmget, prctl, ...
    LRT_DENY,
};

#undef LRT_ALLOW
#undef LRT_DENY
#undef LRT_RETURN
#undef LRT_LOAD

// What this code may use: no C library, no stack protector (its canary is in
// TLS, not set up yet), no instrumentation that calls into a runtime.
#define LRT_BARE __attribute__((no_stack_protector, no_instrument_function, noinline))

LRT_BARE long Call(long nr, long a = 0, long b = 0, long c = 0) {
    long result;
    register long r10 __asm__("r10") = 0;
    register long r8 __asm__("r8") = 0;
    __asm__ __volatile__("syscall"
                         : "=a"(result)
                         : "a"(nr), "D"(a), "S"(b), "d"(c), "r"(r10), "r"(r8)
                         : "rcx", "r11", "memory");
    return result;
}

const char kRefused[] =
    "worker: the kernel refused the system-call filter (seccomp) that must be "
    "in place before the student's code runs; the worker does not run without "
    "it (tests/calls/wall.cpp)\n";

}  // namespace

// Installs the filter, or ends the process. Called by lrt_wall_entry before
// anything else of the program.
extern "C" LRT_BARE void lrt_wall_install() {
    // Without privileges to gain (also what lets an unprivileged process
    // install a filter): setuid programs no longer raise them.
    bool ok = Call(__NR_prctl, PR_SET_NO_NEW_PRIVS, 1) == 0;
    if (ok) {
        long pid = Call(__NR_getpid);
        filter[kOwnPidAt].k = unsigned(pid);
        sock_fprog program;
        program.len = (unsigned short)(sizeof(filter) / sizeof(filter[0]));
        program.filter = filter;
        ok = Call(__NR_seccomp, SECCOMP_SET_MODE_FILTER, 0, long(&program)) == 0 ||
             Call(__NR_prctl, PR_SET_SECCOMP, SECCOMP_MODE_FILTER, long(&program)) == 0;
    }
    if (!ok) {
        Call(__NR_write, 2, long(kRefused), long(sizeof(kRefused) - 1));
        for (;;) Call(__NR_exit_group, LRT_WALL_REFUSED);
    }
}

// The entry point. The kernel starts the process here with the stack pointer
// at argc (argv, the environment and the auxiliary vector above it) and %rdx
// holding a function for atexit (0 for a static program); _start reads both.
// Both are kept in callee-saved registers across the call, and the stack
// pointer, 16-byte aligned at entry as a call needs, is given back as it was.
__asm__(R"(
    .text
    .globl lrt_wall_entry
    .type lrt_wall_entry, @function
lrt_wall_entry:
    mov %rsp, %r12
    mov %rdx, %r13
    call lrt_wall_install
    mov %r13, %rdx
    mov %r12, %rsp
    jmp _start
    .size lrt_wall_entry, . - lrt_wall_entry
)");
