"""Temporary files and folders beside their targets, and their cleanup (docs/reliability.md).

Every output is written under a temporary name in its target's folder, flushed and fsynced, then
renamed onto the target, so a reader sees the old file or the new one, never a part. A temporary
name is short (it fits beside any legal target name) and carries the id of the process that writes
it: `.delvjax-<pid>-<random>.part`. The first time a process makes a temporary in a folder it
removes the temporaries there of processes that no longer run (left by SIGKILL). SIGTERM is turned
into `Terminated` (`terminate_as_interrupt`), so the `finally` blocks remove their temporaries.
"""

from __future__ import annotations

import os
import re
import secrets
import shutil
import signal
import threading
from pathlib import Path

PREFIX = ".delvjax-"
SUFFIX = ".part"
_OURS = re.compile(re.escape(PREFIX) + r"(\d+)-[0-9a-f]+" + re.escape(SUFFIX) + r"$")
_UMASK = os.umask(0)  # read once, at import: os.umask sets while it reads, which races with writer threads
os.umask(_UMASK)
_swept: set[str] = set()  # folders whose stale temporaries this process removed already
_lock = threading.Lock()


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised in the main thread like Ctrl-C, so that every `finally` block runs."""


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # e.g. PermissionError: a process of another user has that id
        return True
    return True


def remove_stale(folder: str | Path) -> list[Path]:
    """Remove the temporaries in `folder` whose writing process no longer runs; returns them."""
    gone = []
    try:
        entries = list(Path(folder).iterdir())
    except OSError:
        return gone
    for p in entries:
        m = _OURS.match(p.name)
        if m is None or _alive(int(m.group(1))):
            continue
        try:
            shutil.rmtree(p) if p.is_dir() and not p.is_symlink() else p.unlink()
            gone.append(p)
        except OSError:  # another process removed it first, or it cannot be removed: leave it
            pass
    return gone


def _sweep_once(folder: Path) -> None:
    key = os.path.realpath(folder)
    with _lock:
        if key in _swept:
            return
        _swept.add(key)
    remove_stale(folder)


def temp_name(folder: str | Path) -> Path:
    """A fresh temporary name in `folder` (nothing is created)."""
    return Path(folder) / f"{PREFIX}{os.getpid()}-{secrets.token_hex(6)}{SUFFIX}"


def new_temp_file(folder: str | Path) -> Path:
    """Create an empty temporary file in `folder` (exclusively) and return its path."""
    _sweep_once(Path(folder))
    while True:
        path = temp_name(folder)
        try:
            os.close(os.open(path, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o600))
            return path
        except FileExistsError:  # pragma: no cover - 48 random bits
            continue


def new_temp_dir(folder: str | Path) -> Path:
    """Create an empty temporary folder in `folder` and return its path."""
    _sweep_once(Path(folder))
    path = temp_name(folder)
    path.mkdir(mode=0o700)
    return path


def ordinary_permissions(path: str | Path) -> None:
    """Give a temporary (made 0600 / 0700) the permissions of an ordinary file or folder under the umask."""
    os.chmod(path, (0o777 if Path(path).is_dir() else 0o666) & ~_UMASK)


def fsync_path(path: str | Path) -> None:
    """Flush a written file (or a folder's entries) to the disk."""
    flags = os.O_RDONLY | (os.O_DIRECTORY if Path(path).is_dir() else 0)
    fd = os.open(path, flags)
    try:
        os.fsync(fd)
    except OSError:  # a file system without fsync for folders: the rename is still atomic
        pass
    finally:
        os.close(fd)


def fsync_tree(folder: str | Path) -> None:
    """fsync every file of a folder and the folder itself (a database before it is renamed into place)."""
    for p in Path(folder).rglob("*"):
        if p.is_file():
            fsync_path(p)
    fsync_path(folder)


def _raise_terminated(signum, frame) -> None:
    raise Terminated()


def terminate_as_interrupt() -> None:
    """Turn SIGTERM into `Terminated` in the main thread (the command line installs this)."""
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGTERM, _raise_terminated)
