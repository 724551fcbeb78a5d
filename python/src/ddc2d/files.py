"""Write files the way ddc2d writes its results
(docs/output-reference.md#how-the-file-is-written), for every file the scripts write.

Only regular files are ever replaced. The target is the path with its symbolic links
followed (the link stays, the file it points to is written); a folder, device, FIFO or
socket there is refused with an OSError that says so. The file is written under a temporary
name in the target's folder and renamed onto it only when complete; on any failure the
temporary file is removed and the target is left as it was.

    with atomic_path(path) as temporary:      # a Path to write to, e.g. figure.savefig
        figure.savefig(temporary, format="png")
    write_text_atomically(path, text)
"""

import contextlib
import errno
import os
import stat
import tempfile
from pathlib import Path

KINDS = ((stat.S_ISDIR, "folder"), (stat.S_ISCHR, "character device"),
         (stat.S_ISBLK, "block device"), (stat.S_ISFIFO, "FIFO (named pipe)"),
         (stat.S_ISSOCK, "socket"))


def regular_target(path):
    """The file that writing path replaces: path with its links followed; OSError when
    that is not a regular file (an absent one is fine)."""
    final = Path(os.path.realpath(path))
    try:
        mode = os.stat(final).st_mode
    except FileNotFoundError:
        return final
    if stat.S_ISREG(mode):
        return final
    kind = next((name for test, name in KINDS if test(mode)), "special file")
    shown = str(path) if final == Path(path).absolute() else f"{path} (a link to {final})"
    raise OSError(errno.EISDIR if stat.S_ISDIR(mode) else errno.EINVAL,
                  f"{shown} is a {kind}, not a regular file: only regular files are written")


def _umask():
    mask = os.umask(0)
    os.umask(mask)
    return mask


@contextlib.contextmanager
def atomic_path(path):
    """A temporary Path beside the target of path; renamed onto the target when the block
    ends without an exception, removed otherwise."""
    final = regular_target(path)
    handle, name = tempfile.mkstemp(dir=final.parent, prefix=f".{final.name}.",
                                    suffix=".partial")
    os.close(handle)
    temporary = Path(name)
    try:
        yield temporary
        regular_target(final)  # nothing else has appeared there meanwhile
        os.chmod(temporary, 0o666 & ~_umask())
        os.replace(temporary, final)
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise


def write_text_atomically(path, text, newline=None):
    """Write text to path (see atomic_path)."""
    with atomic_path(path) as temporary, open(temporary, "w", newline=newline) as stream:
        stream.write(text)
