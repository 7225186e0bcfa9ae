"""What the scripts that read slipfront recordings through the official Rerun SDK share: the
SDK itself (exit 3 if it is missing, so that the calling test skips) and a dataset server on a
free local port."""

import socket
import sys

try:
    import rerun as rr
except ImportError:
    print("rerun-sdk is not installed", file=sys.stderr)
    sys.exit(3)


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def server(datasets: dict) -> "rr.server.Server":
    """A dataset server over `datasets` (name -> file list or folder), as a context manager."""
    return rr.server.Server(host="127.0.0.1", port=free_port(), datasets=datasets)
