"""Run a command on a two-node (or one-node) Ray cluster on this machine, inside network and
process namespaces of its own.

Ray binds to the machine's outward address even when told 127.0.0.1; in a fresh network
namespace with only the loopback device up, both nodes report 127.0.0.1 and all of the
cluster's traffic stays on loopback. The namespace also has its own process ids, so tearing
it down ends every process the cluster started (``ray stop --force`` there sees only them),
whatever happened to the command. Needs root (``unshare``) and ``ip`` (Debian's iproute2).

The head node gets ``--head-cpus`` CPUs, the second node ``--worker-cpus`` (``--nodes 1``: no
second node, for a figure to set beside the two nodes' on the same machine); the command finds
the cluster at ``127.0.0.1:PORT`` (also in ``RAY_ADDRESS``). With ``--kill-worker-on REGEX``
the second node's raylet is killed when a line of the command's output matches, and the node
is started again ``--restart-after`` seconds later: a node lost in the middle of a run.

Usage::

    python scripts/local_cluster.py -- python scripts/train_rllib.py --address 127.0.0.1:6380
    python scripts/local_cluster.py --kill-worker-on '^iteration 2:' -- python scripts/train_rllib.py ...
"""

from __future__ import annotations

import argparse
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

INSIDE = "--inside-namespace"
PR_SET_PDEATHSIG = 1
WORKER_NAME = "worker"
"""The ``--node-name`` of the second node: how its raylet is told apart from the head's."""


def build_parser() -> argparse.ArgumentParser:
    """The command line of this script."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--port", type=int, default=6380, help="the head node's GCS port")
    parser.add_argument("--head-cpus", type=int, default=1)
    parser.add_argument("--worker-cpus", type=int, default=1)
    parser.add_argument("--nodes", type=int, choices=(1, 2), default=2)
    parser.add_argument("--kill-worker-on", metavar="REGEX",
                        help="kill the second node's raylet when a line of the command's output matches")
    parser.add_argument("--restart-after", type=float, default=5.0,
                        help="seconds after the kill at which the second node is started again")
    parser.add_argument(INSIDE, action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("command", nargs=argparse.REMAINDER, help="the command to run on the cluster (after --)")
    return parser


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


def inside(args: argparse.Namespace) -> int:
    """In the namespaces: loopback up, two nodes, the command, then every Ray process stopped."""
    subprocess.run(["ip", "link", "set", "lo", "up"], check=True)
    temp_dir = tempfile.mkdtemp(prefix="netgym-ray-")  # short: Ray's socket paths must fit 107 bytes
    try:
        start_node(args.port, args.head_cpus, head=True, temp_dir=temp_dir)
        if args.nodes == 2:
            start_node(args.port, args.worker_cpus, head=False, temp_dir=temp_dir)
        cpus = f"{args.head_cpus} + {args.worker_cpus}" if args.nodes == 2 else f"{args.head_cpus}"
        print(f"local_cluster: {args.nodes} node(s) up at 127.0.0.1:{args.port} ({cpus} CPUs; temp dir {temp_dir})",
              flush=True)
        pattern = None if args.kill_worker_on is None else re.compile(args.kill_worker_on)
        return run_command(args.command, args.port, pattern, args.worker_cpus, args.restart_after, temp_dir)
    finally:
        subprocess.run([ray_cli(), "stop", "--force"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        shutil.rmtree(temp_dir, ignore_errors=True)


def main() -> None:
    """Parse arguments; outside the namespaces, enter them by running this script again there."""
    parser = build_parser()
    args = parser.parse_args()
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    if not command:
        parser.error("no command to run: give it after --")
    if args.kill_worker_on is not None and args.nodes == 1:
        parser.error("--kill-worker-on needs the second node (--nodes 2)")
    args.command = command
    if args.inside_namespace:
        sys.exit(inside(args))
    try:
        check_tools()
    except (FileNotFoundError, PermissionError) as error:
        parser.error(str(error))
    # -n: network namespace (loopback only); -p -f --mount-proc: process ids of its own, so that
    # every process left in it ends when its first process (this script, again) exits.
    # --kill-child, and unshare itself killed with this process: nothing outlives a killed run.
    sys.exit(subprocess.run(["unshare", "-n", "-p", "-f", "--mount-proc", "--kill-child",
                             sys.executable, *sys.argv[:1], INSIDE, *sys.argv[1:]],
                            preexec_fn=die_with_parent).returncode)


if __name__ == "__main__":
    main()
