"""``python -m agents``: the main job on the default scene.

Loads the pretrained PPO model shipped in ``agents/pretrained/`` (or trains one with
``--train``, or when none is there), then evaluates it beside the ballistic oracle and the
random policy on the same seeded episodes, printing capture rates with 95% confidence
intervals and throughput (numba's compiling of kernels met first in the timed episodes left out,
and said).
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

from agents.evaluation import evaluate
from agents.policies import PRETRAINED, TRAIN_EXTRA, load_policy
from agents.warm_up import compile_kernels
from netgym.bench.results import write_results
from netgym.physics.compile_notice import compile_seconds


def main() -> None:
    """Train or load, then evaluate."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--episodes", type=int, default=100, help="seeded evaluation episodes per policy")
    parser.add_argument("--train", action="store_true", help="train a new model even if one is shipped")
    parser.add_argument("--minutes", type=float, default=20.0, help="training budget when training")
    parser.add_argument("--results", type=Path, help="also write the capture rates to this result file (JSON)")
    args = parser.parse_args()
    model_path = PRETRAINED
    if args.train or not PRETRAINED.exists():
        try:
            from agents.training import train
        except ImportError as missing:
            raise SystemExit(f"training needs {TRAIN_EXTRA}") from missing
        out = Path("runs/ppo")
        print(f"training PPO for up to {args.minutes:g} min (TensorBoard logs in {out / 'tb'}) ...")
        train(out, minutes=args.minutes)
        model_path = out / "best_model.zip"
    print(f"NetCatch-v0, scene basket, {args.episodes} episodes x 3 throws, seeds 10000..{10000 + args.episodes - 1}")
    start = time.perf_counter()
    compile_kernels()  # outside the timings
    print(f"  simulator ready in {time.perf_counter() - start:.1f} s")
    rates = {}
    for name in (str(model_path), "oracle", "random"):
        start = time.perf_counter()
        try:
            policy = load_policy(name)
        except ImportError as missing:  # the environment alone was installed, without the [train] extra
            raise SystemExit(str(missing)) from missing
        loaded, compiled = time.perf_counter(), compile_seconds()
        label = "PPO " + Path(name).name if name.endswith(".zip") else name
        result = evaluate(policy, args.episodes, seed=10_000, progress=label)
        compiling = compile_seconds() - compiled  # kernels only this policy's throws need: not the env's pace
        rate = result.throws / (time.perf_counter() - loaded - compiling)
        load = f"; loaded in {loaded - start:.1f} s" if loaded - start >= 0.05 else ""
        left_out = f"; {compiling:.1f} s of compiling left out" if compiling >= 0.05 else ""
        print(f"  {label:<24} capture rate {result}  [{rate:.0f} throws/s{load}{left_out}]")
        rates[label] = {**dataclasses.asdict(result), "throws_per_s": rate}
    if args.results is not None:
        figures = {"env": "NetCatch-v0", "episodes": args.episodes, "seeds": [10_000, 10_000 + args.episodes - 1],
                   "policies": rates}
        print(f"wrote {write_results(args.results, figures, ['-m', 'agents', *sys.argv[1:]])}")


if __name__ == "__main__":
    main()
