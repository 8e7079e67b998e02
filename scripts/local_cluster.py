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
import subprocess
import sys

from agents.local_cluster import check_tools, die_with_parent, inside

INSIDE = "--inside-namespace"


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
        sys.exit(inside(command, args.port, args.head_cpus, args.worker_cpus, args.nodes, args.kill_worker_on,
                        args.restart_after))
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
