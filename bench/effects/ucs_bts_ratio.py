#!/usr/bin/env python3
"""Does an effect move the UCS/BTS ratio? (docs/effects.md, "interaction_range and rolling_resistance")

For each packing in --packings and each effect setting in --effects, runs UCTs (H = 2D) and
flattened-disc BTTs (t = D/2, the default geometry) at D/R --size on --seeds seeds, and prints the
ensemble mean +- standard error of UCS and BTS, their ratio with its propagated error, the UCT
modulus, the bonds per particle and the share of runs that reached a peak with failure.

  bench/effects/ucs_bts_ratio.py [--build build] [--out runs/effects] [--size 20] [--seeds 5]
      [--packings fcc,random] [--bond 64,128] [--jobs 2]
      [--effects none,interaction_range:factor=1.5,rolling_resistance:mu_r=0.3]

Runs are kept in OUT/NAME/ (NAME from the spec), so a rerun only runs what is missing; delete OUT
after rebuilding the engine.
"""
import argparse
import concurrent.futures
import copy
import json
import math
import os
import statistics

from engine_runs import parse_effect, run_job

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def labelled(text):
    name, effects = parse_effect(text)
    return text.replace(":", "_").replace("=", "").replace(";", "_"), effects


def job(test, packing, size, seed, bond, effects):
    sample = {"diameter": size, "packing": packing, "radius": 1.0, "seed": seed}
    if packing == "random":
        sample["radius_ratio"] = 1.5
    if test == "uct":
        sample["height"] = 2 * size
    else:
        sample["thickness"] = size / 2
    spec = {"test": test, "sample": sample,
            "material": {"density": 1.0, "kr": 8000, "nu": 0.2},
            "bond": {"fr0": bond[0], "fs0": bond[1]}, "contact": {"friction": 0.6},
            "loading": {"platen_velocity": 0.05, "dt": "auto", "stop_load_fraction": 0.7,
                        "max_strain": 0.2 if test == "uct" else 0.1},
            "damping": {"local": 0.7}}
    if effects:
        spec["effects"] = copy.deepcopy(effects)
    return spec


def mean_se(values):
    if not values:
        return float("nan"), float("nan")
    m = statistics.mean(values)
    se = statistics.stdev(values) / math.sqrt(len(values)) if len(values) > 1 else float("nan")
    return m, se


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "runs", "effects"))
    ap.add_argument("--size", type=float, default=20)
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--packings", default="fcc,random")
    ap.add_argument("--bond", default="64,128")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--effects",
                    default="none,interaction_range:factor=1.5,rolling_resistance:mu_r=0.3")
    a = ap.parse_args()
    engine = os.path.join(a.build, "engine", "rockcal-dem")
    bond = [float(x) for x in a.bond.split(",")]
    effects = [labelled(e) for e in a.effects.split(",")]
    runs = []
    for packing in a.packings.split(","):
        for label, eff in effects:
            for test in ("uct", "btt"):
                for seed in range(1, a.seeds + 1):
                    name = f"{packing}_{label}_{test}_{seed}"
                    runs.append((name, job(test, packing, a.size, seed, bond, eff)))
    os.makedirs(a.out, exist_ok=True)

    def run(item):
        name, spec = item
        return name, run_job(engine, os.path.join(a.out, name), spec)

    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        results = dict(pool.map(run, runs))

    print("| packing | effect | UCS | BTS | UCS/BTS | E | bonds a particle | peaks |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for packing in a.packings.split(","):
        for label, _ in effects:
            row = {}
            for test in ("uct", "btt"):
                rs = [results[f"{packing}_{label}_{test}_{s}"] for s in range(1, a.seeds + 1)]
                ok = [r for r in rs if r.get("peak_reached")]
                row[test] = (mean_se([r["strength"] for r in ok]), len(ok), rs)
            (u, u_se), nu, urs = row["uct"]
            (b, b_se), nb, _ = row["btt"]
            ratio = u / b
            r_se = ratio * math.hypot(u_se / u, b_se / b)
            moduli = [r["youngs_modulus"] for r in urs if r.get("youngs_modulus")]
            e = statistics.mean(moduli) if moduli else float("nan")
            coordination = 2 * urs[0]["bonds"] / urs[0]["particles"]
            print(f"| {packing} | {label} | {u:.2f} +- {u_se:.2f} | {b:.2f} +- {b_se:.2f} | "
                  f"{ratio:.2f} +- {r_se:.2f} | {e:.0f} | {coordination:.2f} | "
                  f"{nu + nb}/{2 * a.seeds} |")


if __name__ == "__main__":
    main()
