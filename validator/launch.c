/* rrt-validator's launcher: starts the planner before the interpreter starts.

   ./rrt-validator execs it (when built: tools/build_launcher.py) as
       rrt-validator-launch PYTHON CODE HERE [ARGS...]
   and it execs PYTHON -S -I -B -c CODE HERE [TOKEN] ARGS..., as the script itself
   would. When ARGS hold "--" with a command after it and the problem on stdin is a
   regular file of at most MAX_PROBLEM_BYTES, it first does what
   validator/run_planner.py's start_planner does, so that the planner runs while the
   interpreter starts, instead of after it (docs/setup-and-startup.md): it copies the problem into a sealed memfd (what the validator judges: a
   planner that rewrites the file changes nothing), makes itself a child subreaper,
   starts the command in its own session with the problem's bytes on a pipe to its
   stdin and its stdout and stderr on pipes, with SIGKILL as its parent-death signal,
   SIGPIPE and SIGXFSZ at their defaults, no other file open, found on PATH as
   Popen finds it; then TOKEN tells the interpreter (validator/launched.py) the
   planner's pid, the fds and when it started. Anything else (no "--", a problem on a
   pipe or terminal, a closed standard fd, a command that cannot be executed, any
   failing call): nothing started, the interpreter is execed without TOKEN, with
   stdin as it came (the problem is read with pread), and does it all itself.

   The validator takes the planner over only when TOKEN carries this file's content
   key (RRT_LAUNCH_KEY, set by the build) and the bytes given to the planner are those
   it would give (a grid problem as format_problem writes it; else it stops this run
   and starts the planner again itself). */

#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include <linux/close_range.h>

#ifndef RRT_LAUNCH_KEY
#error "build with -DRRT_LAUNCH_KEY=\"...\" (tools/build_launcher.py)"
#endif

#define MAX_PROBLEM_BYTES (64L * 1024 * 1024) /* cli_common.MAX_PROBLEM_BYTES */
#define SEALS (F_SEAL_SEAL | F_SEAL_SHRINK | F_SEAL_GROW | F_SEAL_WRITE)

static char *const *python_argv(char **argv, int argc, const char *token) {
    /* PYTHON -S -I -B -c CODE HERE [TOKEN] ARGS... (argv: launcher PYTHON CODE HERE ARGS) */
    char **out = calloc((size_t)argc + 6, sizeof *out);
    int n = 0;
    if (out == NULL) return NULL;
    out[n++] = argv[1];
    out[n++] = "-S";
    out[n++] = "-I";
    out[n++] = "-B";
    out[n++] = "-c";
    out[n++] = argv[2];
    out[n++] = argv[3];
    if (token != NULL) out[n++] = (char *)token;
    for (int i = 4; i < argc; i++) out[n++] = argv[i];
    out[n] = NULL;
    return out;
}

static int run_python(char **argv, int argc, const char *token) {
    char *const *args = python_argv(argv, argc, token);
    if (args != NULL) execv(argv[1], args);
    fprintf(stderr, "rrt-validator: cannot run %s: %s\n", argv[1], strerror(errno));
    return 127;
}

static int command_start(int argc, char **argv) {
    /* The index of the planner's command (after the first "--" of ARGS), or 0. */
    for (int i = 4; i < argc; i++)
        if (strcmp(argv[i], "--") == 0) return i + 1 < argc ? i + 1 : 0;
    return 0;
}

static char *read_problem(long *size) {
    /* Stdin's bytes from its offset to its end, when it is a regular file and they are
       within the cap (pread: the offset stays where it was, for the interpreter). */
    struct stat st;
    off_t at = lseek(0, 0, SEEK_CUR);
    if (fstat(0, &st) != 0 || !S_ISREG(st.st_mode) || at < 0 || at > st.st_size ||
        st.st_size - at > MAX_PROBLEM_BYTES)
        return NULL;
    long cap = (long)(st.st_size - at), got = 0;
    char *data = malloc((size_t)cap + 1);
    if (data == NULL) return NULL;
    for (;;) {  /* to the end, which may have moved since fstat: then not at all */
        ssize_t n = pread(0, data + got, (size_t)(cap + 1 - got), at + got);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 || got + n > cap) { free(data); return NULL; }
        if (n == 0) break;
        got += n;
    }
    *size = got;
    return data;
}

static int sealed_copy(const char *data, long size) {
    /* A memfd holding data, sealed against any change, at offset 0; -1 on failure. */
    int fd = memfd_create("rrt-validator-problem", MFD_CLOEXEC | MFD_ALLOW_SEALING);
    long put = 0;
    if (fd < 0) return -1;
    while (put < size) {
        ssize_t n = write(fd, data + put, (size_t)(size - put));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) { close(fd); return -1; }
        put += n;
    }
    if (fcntl(fd, F_ADD_SEALS, SEALS) != 0 || lseek(fd, 0, SEEK_SET) != 0) {
        close(fd);
        return -1;
    }
    return fd;
}

static void report(int fd, int error, const char *stage) {
    char line[64];
    int n = snprintf(line, sizeof line, "%d:%s", error, stage);
    if (n > 0) (void)!write(fd, line, (size_t)n);
}

static void close_all_but(int keep) {
    /* Every fd from 3 up but keep (os.closerange's way: close_range, else one by one). */
    if ((keep == 3 || close_range(3, (unsigned)keep - 1, 0) == 0) &&
        close_range((unsigned)keep + 1, ~0U, 0) == 0)
        return;
    for (long fd = 3, last = sysconf(_SC_OPEN_MAX); fd < last; fd++)
        if (fd != keep) close((int)fd);
}

static void exec_child(int ends[3], int error_write, pid_t parent, char **command) {
    /* In the forked child, as run_planner._exec_child: never returns. */
    int saved = 0, error = 0;
    for (int i = 0; i < 3; i++)
        while (ends[i] <= 2) {  /* off 0-2 first, so that no dup2 below overwrites it */
            ends[i] = dup(ends[i]);
            if (ends[i] < 0) goto failed;
        }
    for (int i = 0; i < 3; i++)
        if (dup2(ends[i], i) < 0) goto failed;
    signal(SIGPIPE, SIG_DFL);
    signal(SIGXFSZ, SIG_DFL);
    if (setsid() < 0) goto failed;
    if (prctl(PR_SET_PDEATHSIG, SIGKILL, 0, 0, 0) != 0) goto failed;
    if (getppid() != parent) kill(getpid(), SIGKILL);  /* the parent died meanwhile */
    close_all_but(error_write);
    if (strchr(command[0], '/') != NULL) {
        execv(command[0], command);
        error = errno;
    } else {  /* PATH as os.get_exec_path(): its folders, or os.defpath's */
        const char *path = getenv("PATH");
        char *folders = strdup(path != NULL ? path : "/bin:/usr/bin"), *rest = folders;
        char *folder, full[4096];
        if (folders == NULL) goto failed;
        while ((folder = strsep(&rest, ":")) != NULL) {
            /* os.path.join(folder, name): an empty folder is the current one */
            int n = snprintf(full, sizeof full, "%s%s%s", folder, *folder ? "/" : "",
                             command[0]);
            if (n < 0 || n >= (int)sizeof full) error = ENAMETOOLONG;
            else {
                execv(full, command);
                error = errno;
            }  /* as Popen: the first error but "not there", else the last */
            if (saved == 0 && error != ENOENT && error != ENOTDIR) saved = error;
        }
    }
    report(error_write, saved != 0 ? saved : error, "exec");
    _exit(255);
failed:
    report(error_write, errno, "noexec");
    _exit(255);
}

static int inherited(int fd) {
    /* fd kept open across the interpreter's exec (pipe2 made it close-on-exec). */
    int flags = fcntl(fd, F_GETFD);
    return flags >= 0 && fcntl(fd, F_SETFD, flags & ~FD_CLOEXEC) == 0;
}

struct run {
    pid_t pid;
    int stdin_fd, stdout_fd, stderr_fd; /* our ends of its pipes; stdin -1 once closed */
    long written;                      /* the problem's bytes written to its stdin */
    struct timespec began;
};

static int spawn(char **command, struct run *run) {
    /* The planner started as _spawn starts it: 0, or -1 with nothing left open or
       running (a command that cannot be executed: the interpreter starts it and says
       why, in Popen's words). */
    int pipes[8], made = 0;  /* stdin, stdout, stderr, the exec's error report */
    while (made < 4 && pipe2(pipes + 2 * made, O_CLOEXEC) == 0) made++;
    clock_gettime(CLOCK_MONOTONIC, &run->began);
    pid_t parent = getpid(), pid = made == 4 ? fork() : -1;
    if (pid == 0) {
        int ends[3] = {pipes[0], pipes[3], pipes[5]};
        exec_child(ends, pipes[7], parent, command);
    }
    for (int i = 0; i < 2 * made; i++)
        if (pid < 0 || i == 0 || i == 3 || i == 5 || i == 7) close(pipes[i]);
    if (pid < 0) return -1;
    char reported[64];
    ssize_t got;
    do got = read(pipes[6], reported, sizeof reported);
    while (got < 0 && errno == EINTR);
    close(pipes[6]);
    if (got != 0) {  /* EOF at once: the exec took place */
        waitpid(pid, NULL, 0);
        close(pipes[1]), close(pipes[2]), close(pipes[4]);
        return -1;
    }
    run->pid = pid, run->stdin_fd = pipes[1], run->stdout_fd = pipes[2];
    run->stderr_fd = pipes[4], run->written = 0;
    return 0;
}

static void feed(struct run *run, const char *data, long size) {
    /* What the stdin pipe takes without waiting; closed when all is written or the
       planner closed its end (EPIPE: its business, as for the interpreter). */
    struct sigaction ignore = {.sa_handler = SIG_IGN}, before;
    int error = 0;
    sigaction(SIGPIPE, &ignore, &before);
    fcntl(run->stdin_fd, F_SETFL, fcntl(run->stdin_fd, F_GETFL) | O_NONBLOCK);
    while (run->written < size) {
        ssize_t n = write(run->stdin_fd, data + run->written, (size_t)(size - run->written));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            error = errno;
            break;
        }
        run->written += n;
    }
    sigaction(SIGPIPE, &before, NULL);
    if (run->written == size || error == EPIPE) {
        close(run->stdin_fd);
        run->stdin_fd = -1;
    }
}

int main(int argc, char **argv) {
    if (argc < 4) {
        fprintf(stderr, "rrt-validator-launch: run by ./rrt-validator\n");
        return 2;
    }
    int start = command_start(argc, argv), memfd = -1;
    struct stat st;
    struct run run;
    long size = 0;
    if (start == 0 || fstat(1, &st) != 0 || fstat(2, &st) != 0)
        return run_python(argv, argc, NULL);
    char *problem = read_problem(&size);
    if (problem != NULL) memfd = sealed_copy(problem, size);
    if (memfd < 0 || prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0) != 0)
        return run_python(argv, argc, NULL);  /* (the memfd closes on exec) */
    if (spawn(argv + start, &run) != 0) {
        prctl(PR_SET_CHILD_SUBREAPER, 0, 0, 0, 0);
        return run_python(argv, argc, NULL);
    }
    feed(&run, problem, size);
    if ((run.stdin_fd >= 0 && !inherited(run.stdin_fd)) || !inherited(run.stdout_fd) ||
        !inherited(run.stderr_fd) || !inherited(memfd)) {
        kill(-run.pid, SIGKILL);  /* it cannot be handed over: the interpreter starts it */
        waitpid(run.pid, NULL, 0);
        prctl(PR_SET_CHILD_SUBREAPER, 0, 0, 0, 0);
        return run_python(argv, argc, NULL);
    }
    char token[256];
    snprintf(token, sizeof token, "--rrt-validator-launched=%s:%d:%d:%ld:%d:%d:%d:%lld",
             RRT_LAUNCH_KEY, (int)run.pid, run.stdin_fd, run.written, run.stdout_fd,
             run.stderr_fd, memfd,
             (long long)run.began.tv_sec * 1000000000LL + run.began.tv_nsec);
    return run_python(argv, argc, token);
}
