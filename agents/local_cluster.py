"""A Ray cluster of one or two nodes on this machine, inside network and process namespaces of
its own (``scripts/local_cluster.py`` enters them and runs a command there): Ray binds to the
machine's outward address even when told 127.0.0.1; in a fresh network namespace with only the
loopback device up, all of the cluster's traffic stays on loopback, and tearing the namespace
down ends every process the cluster started. Needs root (``unshare``) and ``ip`` (iproute2)."""

from __future__ import annotations

import ctypes
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

PR_SET_PDEATHSIG = 1
WORKER_NAME = "worker"
"""The ``--node-name`` of the second node: how its raylet is told apart from the head's."""


def ray_cli() -> str:
    """The ``ray`` command of this Python's environment."""
    found = shutil.which("ray", path=str(Path(sys.executable).parent)) or shutil.which("ray")
    if found is None:
        raise FileNotFoundError('the ray command is missing: pip install -e ".[rllib]"')
    return found


def die_with_parent() -> None:
    """In a child before it runs its program: be killed when this process dies (Linux prctl)."""
    ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)


def check_tools() -> None:
    """Raise a clear error unless ``unshare`` and ``ip`` are there and this process is root."""
    for tool, package in (("unshare", "util-linux"), ("ip", "iproute2")):
        if shutil.which(tool) is None:
            raise FileNotFoundError(f"the {tool} command is missing (Debian package {package})")
    if os.geteuid() != 0:
        raise PermissionError("a network namespace of its own needs root (unshare -n)")


def start_node(port: int, cpus: int, head: bool, temp_dir: str) -> None:
    """``ray start`` a head node on ``port`` or a second node joining it, with ``cpus`` CPUs,
    its sessions and sockets under ``temp_dir``."""
    where = ["--head", f"--port={port}", "--include-dashboard=false"] if head else [
        f"--address=127.0.0.1:{port}", f"--node-name={WORKER_NAME}"]
    subprocess.run([ray_cli(), "start", *where, "--node-ip-address=127.0.0.1", f"--num-cpus={cpus}",
                    f"--temp-dir={temp_dir}", "--disable-usage-stats"], check=True, stdout=subprocess.DEVNULL)


def worker_raylets() -> list[int]:
    """Process ids of the second node's raylet (this namespace's /proc)."""
    found = []
    for entry in Path("/proc").iterdir():
        try:
            words = (entry / "cmdline").read_bytes().split(b"\0")
        except (OSError, ValueError):
            continue
        if words and words[0].endswith(b"raylet") and f"--node-name={WORKER_NAME}".encode() in words:
            found.append(int(entry.name))
    return found


def run_command(command: list[str], port: int, kill_on: re.Pattern[str] | None, worker_cpus: int,
                restart_after: float, temp_dir: str) -> int:
    """Run ``command``, echoing its output; kill and restart the second node on ``kill_on``."""
    env = {**os.environ, "RAY_ADDRESS": f"127.0.0.1:{port}"}
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env, bufsize=1)
    for line in process.stdout:
        print(line, end="", flush=True)
        if kill_on is not None and kill_on.search(line):
            kill_on = None
            raylets = worker_raylets()
            for pid in raylets:
                os.kill(pid, 9)
            print(f"local_cluster: killed the second node's raylet {raylets} at {time.time():.3f}", flush=True)
            time.sleep(restart_after)
            start_node(port, worker_cpus, head=False, temp_dir=temp_dir)
            print(f"local_cluster: second node started again at {time.time():.3f}", flush=True)
    return process.wait()


def inside(command: list[str], port: int, head_cpus: int, worker_cpus: int, nodes: int,
           kill_worker_on: str | None, restart_after: float) -> int:
    """In the namespaces: loopback up, ``nodes`` nodes (the head with ``head_cpus`` CPUs on
    ``port``, the second with ``worker_cpus``), ``command`` (its second node killed and started
    again ``restart_after`` seconds later when a line of its output matches ``kill_worker_on``),
    then every Ray process stopped; returns the command's exit status."""
    subprocess.run(["ip", "link", "set", "lo", "up"], check=True)
    temp_dir = tempfile.mkdtemp(prefix="netgym-ray-")  # short: Ray's socket paths must fit 107 bytes
    try:
        start_node(port, head_cpus, head=True, temp_dir=temp_dir)
        if nodes == 2:
            start_node(port, worker_cpus, head=False, temp_dir=temp_dir)
        cpus = f"{head_cpus} + {worker_cpus}" if nodes == 2 else f"{head_cpus}"
        print(f"local_cluster: {nodes} node(s) up at 127.0.0.1:{port} ({cpus} CPUs; temp dir {temp_dir})",
              flush=True)
        pattern = None if kill_worker_on is None else re.compile(kill_worker_on)
        return run_command(command, port, pattern, worker_cpus, restart_after, temp_dir)
    finally:
        subprocess.run([ray_cli(), "stop", "--force"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        shutil.rmtree(temp_dir, ignore_errors=True)
