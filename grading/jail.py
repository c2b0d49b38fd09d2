"""Start one submission's program contained:
``python -S -I jail.py KEY=VALUE... -- PROGRAM...``.

Standard library only, and only its fast imports (no ``json``, ``signal``: ``re`` and
``enum`` would double the start-up). The settings (:func:`grading.sandbox.Sandbox.command`
writes them): ``level``, ``folder``, ``source``, ``keep``, ``hide`` (repeated),
``disk``, ``inodes``, ``uid``, ``gid``, ``tmpdir`` and the limits ``cpu``, ``as``,
``fsize``, ``nproc``. Three levels:

- ``full`` (as root): the program runs in its own PID, mount, network, IPC and UTS
  namespaces, as an unprivileged uid of its own with no capabilities and
  ``no_new_privs``; ``/proc`` its namespace's; a minimal ``/dev``; empty private
  ``/tmp``, ``/var/tmp``, ``/run`` and ``/dev/shm``; ``--out`` and the other
  submissions hidden; everything else read-only. Its folder (also ``HOME``) and
  ``/tmp`` live on one private size-capped tmpfs, thrown away at the end. A run
  sees the built folder through an overlay (its changes go to the tmpfs); a build
  works on a copy of the submission, copied to ``keep`` when ``make.sh`` succeeds.
- ``userns`` (not root): the same in a user namespace, but as the grader's own uid.
- ``none``: resource limits, working directory and ``TMPDIR`` only; the program is
  exec'd in place of this process.

In the namespaces this process forks PID 1 (an init of ours, still privileged),
which builds the view, forks the program, reaps, and when the program ends kills
everything left in the namespace; this process waits for PID 1 and ends as the
program ended (its exit status, or the same signal). Killing this process's group
(what the validator's machinery does at a timeout) kills PID 1 and with it the
whole namespace.
"""

from __future__ import annotations

import _signal as signal  # the module without its enums
import ctypes
import os
import resource
import stat
import sys
import warnings  # noqa: F401 (os.execvp imports it; after the uid drop, maybe it cannot)

CLONE_NEWNS, CLONE_NEWUTS, CLONE_NEWIPC = 0x00020000, 0x04000000, 0x08000000
CLONE_NEWUSER, CLONE_NEWPID, CLONE_NEWNET = 0x10000000, 0x20000000, 0x40000000
MS_RDONLY, MS_NOSUID, MS_NODEV, MS_NOEXEC = 1, 2, 4, 8
MS_REMOUNT, MS_BIND, MS_MOVE, MS_REC, MS_PRIVATE = 32, 4096, 8192, 16384, 1 << 18
MOUNT_ATTR_RDONLY, MOUNT_ATTR_NOSUID = 1, 2
AT_FDCWD, AT_RECURSIVE, SYS_MOUNT_SETATTR = -100, 0x8000, 442
PR_SET_PDEATHSIG, PR_SET_DUMPABLE, PR_CAPBSET_DROP, PR_SET_SECUREBITS = 1, 4, 24, 28
PR_SET_NO_NEW_PRIVS, PR_CAP_AMBIENT, PR_CAP_AMBIENT_CLEAR_ALL = 38, 47, 4
SECURE_NOROOT_ALL = 0x3f  # noroot, no_setuid_fixup, keep_caps off: each with its lock
DEVICES = ("null", "zero", "random", "urandom")
COVERED = ("/var/tmp", "/run")  # emptied for every program (with /tmp and /dev/shm)
RLIMITS = {"cpu": resource.RLIMIT_CPU, "as": resource.RLIMIT_AS,
           "fsize": resource.RLIMIT_FSIZE, "nproc": resource.RLIMIT_NPROC}
NUMBERS = {"disk", "inodes", "uid", "gid", *RLIMITS}

_libc = ctypes.CDLL(None, use_errno=True)


class SandboxError(Exception):
    """The sandbox could not be set up (the program did not start)."""


def _check(result: int, what: str) -> None:
    if result != 0:
        error = ctypes.get_errno()
        raise SandboxError(f"{what}: {os.strerror(error)}")


def _mount(source: str, target: str, fstype: str | None, flags: int, data: str = "") -> None:
    _check(_libc.mount(source.encode(), target.encode(),
                       fstype.encode() if fstype else None, ctypes.c_ulong(flags),
                       data.encode() if data else None), f"mount {target}")


def _prctl(option: int, value: int) -> int:
    return _libc.prctl(option, ctypes.c_ulong(value), ctypes.c_ulong(0), ctypes.c_ulong(0),
                       ctypes.c_ulong(0))


def _unshare(flags: int) -> None:
    _check(_libc.unshare(flags), "unshare")


class _MountAttr(ctypes.Structure):
    _fields_ = [("attr_set", ctypes.c_uint64), ("attr_clr", ctypes.c_uint64),
                ("propagation", ctypes.c_uint64), ("userns_fd", ctypes.c_uint64)]


def _read_only_everywhere() -> None:
    """Every mount of this namespace read-only, nosuid and private (one syscall)."""
    attr = _MountAttr(MOUNT_ATTR_RDONLY | MOUNT_ATTR_NOSUID, 0, MS_PRIVATE, 0)
    _check(_libc.syscall(ctypes.c_long(SYS_MOUNT_SETATTR), ctypes.c_int(AT_FDCWD), b"/",
                         ctypes.c_uint(AT_RECURSIVE), ctypes.byref(attr),
                         ctypes.c_size_t(ctypes.sizeof(attr))),
           "mount_setattr (Linux 5.12 or newer)")


def parse(argv: list[str]) -> tuple[dict, list[str]]:
    """The settings (``hide`` a list, numbers as int) and the program."""
    end = argv.index("--")
    spec: dict = {"hide": []}
    for item in argv[:end]:
        key, _, value = item.partition("=")
        if key == "hide":
            spec["hide"].append(value)
        else:
            spec[key] = int(value) if key in NUMBERS else value
    return spec, argv[end + 1:]


def main(argv: list[str]) -> None:
    spec, program = parse(argv[1:])
    if spec["level"] == "none":
        _start_program(spec, program)
    if spec["level"] == "userns":
        _enter_user_namespace()
    _unshare(CLONE_NEWPID)
    read_end, write_end = os.pipe()
    init = os.fork()
    if init == 0:
        os.close(read_end)
        try:
            report = _init(spec, program)
        except BaseException as error:  # noqa: B036 (PID 1 must say why, whatever it is)
            report = f"error {error}"
        os.write(write_end, report.encode(errors="replace"))
        os._exit(0)
    os.close(write_end)
    told = b""
    while chunk := os.read(read_end, 4096):
        told += chunk
    os.waitpid(init, 0)
    _end_as(told.decode(errors="replace"))


def _end_as(report: str) -> None:
    """End this process as the program ended: its exit status or its signal."""
    kind, _, value = report.partition(" ")
    if kind == "exit":
        os._exit(int(value))
    if kind == "signal":
        number = int(value)
        signal.signal(number, signal.SIG_DFL)
        os.kill(os.getpid(), number)
        os._exit(128 + number)
    os.write(2, f"grading sandbox: {value or 'its init died'}\n".encode(errors="replace"))
    os._exit(125)


def _enter_user_namespace() -> None:
    """A user namespace whose root is the caller's uid and gid (no other uid mapped)."""
    uid, gid = os.geteuid(), os.getegid()
    _unshare(CLONE_NEWUSER)
    for name, text in (("setgroups", "deny"), ("uid_map", f"0 {uid} 1"),
                       ("gid_map", f"0 {gid} 1")):
        with open(f"/proc/self/{name}", "w") as file:
            file.write(text)


def _init(spec: dict, program: list[str]) -> str:
    """PID 1: build the view, run the program, kill the rest, keep a build's folder."""
    _prctl(PR_SET_PDEATHSIG, signal.SIGKILL)
    _prctl(PR_SET_DUMPABLE, 0)  # its /proc files stay root's: no reading its descriptors
    os.umask(0o022)  # the folders made on the way to the folder: open to the program's uid
    keep = os.open(spec["keep"], os.O_RDONLY | os.O_DIRECTORY) if spec.get("keep") else None
    _unshare(CLONE_NEWNS | CLONE_NEWNET | CLONE_NEWIPC | CLONE_NEWUTS)
    _build_view(spec)
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # a handler would let the program stop us
    child = os.fork()
    if child == 0:
        _start_program(spec, program)
    while True:
        pid, status = os.wait()
        if pid == child:
            break
    _kill_the_rest()
    if os.WIFSIGNALED(status):
        return f"signal {os.WTERMSIG(status)}"
    code = os.WEXITSTATUS(status)
    if keep is not None and code == 0:
        _keep(spec, keep)
    return f"exit {code}"


def _kill_the_rest() -> None:
    """SIGKILL every other process of the namespace and reap them all."""
    while True:
        try:
            os.kill(-1, signal.SIGKILL)
        except ProcessLookupError:
            pass
        try:
            os.wait()
        except ChildProcessError:
            return


def _build_view(spec: dict) -> None:
    """The program's file system: see the module's docstring."""
    _read_only_everywhere()
    # Opened before /tmp is covered; not through a link (a submission that is a link to a
    # folder of root's would be copied for the program to read).
    source = os.open(spec["source"], os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW)
    source_path = f"/proc/self/fd/{source}"
    _mount("tmpfs", "/tmp", "tmpfs", MS_NOSUID | MS_NODEV,
           f"size={spec['disk']},nr_inodes={spec['inodes']},mode=0755")
    for name, mode in (("tmp", 0o1777), ("shm", 0o1777), ("folder", 0o755), ("dev", 0o755)):
        os.mkdir(f"/tmp/{name}")
        os.chmod(f"/tmp/{name}", mode)
    if spec.get("keep"):
        _copy_in(spec, source_path)
    else:
        _overlay(spec, source_path)
    os.close(source)
    _make_dev("/tmp/dev")
    covers = _cover([*spec["hide"], *COVERED])
    _mount("/tmp/dev", "/dev", None, MS_MOVE)
    folder = spec["folder"]
    target = "/tmp/tmp" + folder[4:] if _under(folder, "/tmp") else folder
    os.makedirs(target, exist_ok=True)
    _mount("/tmp/folder", target, None, MS_MOVE)
    _mount("/tmp/tmp", "/tmp", None, MS_BIND | MS_REC)
    for path in [*covers, "/dev"]:  # the devices are mounts of their own: they still work
        _mount("none", path, None,
               MS_REMOUNT | MS_BIND | MS_RDONLY | MS_NOSUID | MS_NODEV | MS_NOEXEC)
    _mount("proc", "/proc", "proc", MS_NOSUID | MS_NODEV | MS_NOEXEC)


def _under(path: str, folder: str) -> bool:
    return path == folder or path.startswith(folder.rstrip("/") + "/")


def _cover(paths: list[str]) -> list[str]:
    """An empty tmpfs over each folder still visible (outer ones first); the covers."""
    covers = []
    for path in sorted(set(paths), key=lambda p: (p.count("/"), p)):
        if not _under(path, "/tmp") and os.path.isdir(path):
            _mount("tmpfs", path, "tmpfs", MS_NOSUID | MS_NODEV | MS_NOEXEC,
                   "size=1m,nr_inodes=1024,mode=0755")
            covers.append(path)
    return covers


def _make_dev(dev: str) -> None:
    """A tmpfs with null, zero, random and urandom bound from the host, shm, fd links."""
    _mount("tmpfs", dev, "tmpfs", MS_NOSUID | MS_NOEXEC, "size=64k,nr_inodes=64,mode=0755")
    for name in DEVICES:
        os.close(os.open(f"{dev}/{name}", os.O_CREAT | os.O_WRONLY, 0o666))
        _mount(f"/dev/{name}", f"{dev}/{name}", None, MS_BIND)
    os.mkdir(f"{dev}/shm")
    _mount("/tmp/shm", f"{dev}/shm", None, MS_BIND)
    for name, target in (("fd", "/proc/self/fd"), ("stdin", "/proc/self/fd/0"),
                         ("stdout", "/proc/self/fd/1"), ("stderr", "/proc/self/fd/2")):
        os.symlink(target, f"{dev}/{name}")


def _overlay(spec: dict, lower: str) -> None:
    """The built folder read-only under the run's changes, which go to the tmpfs."""
    info = os.stat(lower)
    os.mkdir("/tmp/upper", stat.S_IMODE(info.st_mode))
    os.chown("/tmp/upper", info.st_uid, info.st_gid)
    os.chmod("/tmp/upper", stat.S_IMODE(info.st_mode))
    os.mkdir("/tmp/work", 0o700)

    def escape(path: str) -> str:
        return path.replace("\\", "\\\\").replace(":", "\\:").replace(",", "\\,")
    options = f"lowerdir={escape(lower)},upperdir=/tmp/upper,workdir=/tmp/work"
    if spec["level"] == "userns":
        options += ",userxattr"
    _mount("overlay", "/tmp/folder", "overlay", MS_NOSUID | MS_NODEV, options)


def _copy_in(spec: dict, source: str) -> None:
    """A build's folder: a copy of the submission, owned by the program's uid."""
    owner = (spec["uid"], spec["gid"]) if spec["level"] == "full" else None
    _copy_tree(source, "/tmp/folder", spec["disk"], spec["inodes"], owner,
               _same_mode, "the submission's folder")
    _mount("/tmp/folder", "/tmp/folder", None, MS_BIND)  # a mount, to be moved in place


def _keep(spec: dict, keep: int) -> None:
    """A successful build's folder, copied to ``keep/NAME`` (through the descriptor
    opened before the mount namespace: the grader's own view of it)."""
    name = os.path.basename(spec["folder"])
    base = f"/proc/self/fd/{keep}"
    partial = f"{base}/.{name}.partial"
    owner = (0, spec["gid"]) if spec["level"] == "full" else None
    _copy_tree(spec["folder"], partial, spec["disk"], spec["inodes"], owner,
               _group_as_owner, "the built folder")
    os.rename(partial, f"{base}/{name}")


def _same_mode(mode: int) -> int:
    return mode & 0o777


def _group_as_owner(mode: int) -> int:
    """The owner's permissions also for the group (the runs' shared group), none for others."""
    owner = mode & 0o700
    return owner | owner >> 3


def _copy_tree(source: str, target: str, size: int, count: int, owner, mode_of,
               what: str) -> None:
    """Copy folders, regular files and symbolic links (never followed; anything else
    is skipped) from ``source`` into the folder ``target`` (created if missing), at
    most ``size`` bytes and ``count`` entries."""
    budget = [size, count]
    os.makedirs(target, exist_ok=True)
    stack = [(source, target)]
    while stack:
        src, dst = stack.pop()
        with os.scandir(src) as entries:
            for entry in entries:
                budget[1] -= 1
                if budget[1] < 0:
                    raise SandboxError(f"{what} has more than {count} entries")
                _copy_entry(entry, f"{dst}/{entry.name}", budget, what, owner, mode_of,
                            stack)
        _finish(src, dst, os.stat(src), owner, mode_of)  # the root: a /proc/self/fd link


def _copy_entry(entry, dst: str, budget: list[int], what: str, owner, mode_of,
                stack: list) -> None:
    info = entry.stat(follow_symlinks=False)
    if stat.S_ISDIR(info.st_mode):
        os.mkdir(dst, 0o700)
        stack.append((entry.path, dst))
    elif stat.S_ISLNK(info.st_mode):
        os.symlink(os.readlink(entry.path), dst)
        if owner:
            os.chown(dst, *owner, follow_symlinks=False)
    elif stat.S_ISREG(info.st_mode):
        budget[0] -= info.st_size
        if budget[0] < 0:
            raise SandboxError(f"{what} is larger than the cap")
        _copy_file(entry.path, dst, info.st_size)
        _finish(entry.path, dst, info, owner, mode_of)


def _copy_file(src: str, dst: str, size: int) -> None:
    reader = os.open(src, os.O_RDONLY | os.O_NOFOLLOW)
    try:
        writer = os.open(dst, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o600)
        try:
            while size > 0:
                sent = os.sendfile(writer, reader, None, min(size, 1 << 30))
                if sent == 0:
                    break
                size -= sent
        finally:
            os.close(writer)
    finally:
        os.close(reader)


def _finish(src: str, dst: str, info: os.stat_result, owner, mode_of) -> None:
    """Owner, permissions (set-id bits dropped) and times of a copied file or folder."""
    if owner:
        os.chown(dst, *owner, follow_symlinks=False)
    os.chmod(dst, mode_of(info.st_mode))
    os.utime(dst, ns=(info.st_atime_ns, info.st_mtime_ns), follow_symlinks=False)


def _start_program(spec: dict, program: list[str]) -> None:
    """Limits, folder, identity, then exec the program; never returns."""
    try:
        for signum in (signal.SIGPIPE, signal.SIGXFSZ, signal.SIGINT):
            signal.signal(signum, signal.SIG_DFL)  # as a process started by the shell
        os.chdir(spec["folder"])
        os.environ["TMPDIR"] = spec.get("tmpdir") or "/tmp"
        if spec["level"] != "none":  # the grader's home is out of reach (or read-only)
            os.environ["HOME"] = spec["folder"]
        for name, which in RLIMITS.items():
            if name in spec:
                resource.setrlimit(which, (spec[name], spec[name]))
        if spec["level"] != "none":
            _drop_privileges(spec)
        os.execvp(program[0], program)
    except BaseException as error:  # noqa: B036 (the child must never return)
        os.write(2, f"grading sandbox: cannot start {program[0]}: {error}\n".encode(
            errors="replace"))
    os._exit(127)


def _drop_privileges(spec: dict) -> None:
    """No capabilities (bounding set, ambient set), no_new_privs; ``full``: the run's uid."""
    last = int(open("/proc/sys/kernel/cap_last_cap").read())
    for cap in range(last + 1):
        _check(_prctl(PR_CAPBSET_DROP, cap), "drop a capability")
    _prctl(PR_CAP_AMBIENT, PR_CAP_AMBIENT_CLEAR_ALL)
    _check(_prctl(PR_SET_NO_NEW_PRIVS, 1), "no_new_privs")
    if spec["level"] == "full":
        os.setgroups([])
        os.setresgid(spec["gid"], spec["gid"], spec["gid"])
        os.setresuid(spec["uid"], spec["uid"], spec["uid"])
    else:  # root of the user namespace: no capabilities across exec
        _check(_prctl(PR_SET_SECUREBITS, SECURE_NOROOT_ALL), "securebits")


if __name__ == "__main__":
    main(sys.argv)
