"""`h3ds studio` as a user runs it: both servers up, their URLs printed, busy ports skipped."""

import random
import re
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

from frontend.server import free_port


def fetch(url: str, wait_s: float = 20.0) -> bytes:
    """GET, retrying while the server is still starting."""
    deadline = time.time() + wait_s
    while True:
        try:
            return urllib.request.urlopen(url, timeout=5).read()
        except OSError:
            if time.time() > deadline:
                raise
            time.sleep(0.2)


def test_free_port_skips_a_busy_one():
    with socket.socket() as busy:
        busy.bind(("127.0.0.1", 0))
        busy.listen()
        port = busy.getsockname()[1]
        assert free_port("127.0.0.1", port) > port


def test_studio_command_serves_the_studio_and_the_api(tmp_path):
    port = random.randint(41000, 49000)
    env = {"H3DS_DATA_DIR": str(tmp_path), "PATH": "/usr/bin:/bin"}
    proc = subprocess.Popen([str(Path(sys.executable).parent / "h3ds"), "studio", "--port", str(port)],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    try:
        lines = []
        deadline = time.time() + 60
        while time.time() < deadline and not any(line.startswith("Database:") for line in lines):
            lines.append(proc.stdout.readline().strip())
        text = "\n".join(lines)
        studio_url = re.search(r"H3DS Studio: (\S+)", text).group(1)
        api_url = re.search(r"HTTP API:\s+(\S+)/docs", text).group(1)
        assert str(tmp_path) in text  # the database path is printed
        assert b"<html" in fetch(studio_url).lower()
        assert b'"ok"' in fetch(f"{api_url}/health")
    finally:
        proc.terminate()
        proc.wait(timeout=10)
