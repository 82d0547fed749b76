#!/usr/bin/env python3
"""The "auto" platen speed against a fixed one (docs/loading-rate.md, "The auto speed").

  homogeneity: UCT and BTT at the bond strengths s x (1, --ratio) for each s in --scales, with the
      fixed speed --fixed and with "auto"; prints each peak load and the degree of homogeneity
      p = ln(L(s2) / L(s1)) / ln(s2 / s1) between neighbouring scales and over the whole range.
  rate: UCT and BTT at --bond with "auto" and each loading.auto_transits in --transits (and the
      fixed speed --fixed): peak, change per doubling of the transits, the kinetic / bond energy
      ratio at the peak, steps and wall time.

  bench/auto_speed.py homogeneity [--size 10] [--scales 2,20,200] [--ratio 1] [--seeds 1]
  bench/auto_speed.py rate [--size 20] [--bond 64,64] [--transits 2.5,5,10,20,40]
  common: [--build build] [--out runs/auto_speed] [--fixed 0.05] [--slow-factor 1] [--jobs 1]
          [--max-strain 0.2] [--log FILE]

Specimens: the default ones (seeded FCC, UCT H = 2D, flattened disc t = D/2), K_r 8000, nu 0.2,
R 1, density 1, friction 0.6. Runs are kept in OUT/NAME/, so a rerun only runs what is missing
(delete OUT after rebuilding the engine); --log appends one JSON line per run as it finishes.
"""
import argparse
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench", "effects"))
from engine_runs import add_run_options, run_all  # noqa: E402


def job(test, size, bond, speed, a, seed):
    sample = {"diameter": size, "radius": 1.0, "packing": "fcc", "seed": seed}
    if test == "uct":
        sample["height"] = 2 * size
    loading = {"platen_velocity": speed[0], "dt": "auto", "slow_factor": a.slow_factor,
               "max_strain": a.max_strain}
    if speed[0] == "auto":
        loading["auto_transits"] = speed[1]
        loading["past_window"] = a.past_window
    return {"test": test, "sample": sample,
            "material": {"density": 1.0, "kr": 8000, "nu": 0.2},
            "bond": {"fr0": bond[0], "fs0": bond[1]}, "contact": {"friction": 0.6},
            "loading": loading, "damping": {"local": 0.7}}


def name_of(test, size, bond, speed, seed):
    s = "auto%g" % speed[1] if speed[0] == "auto" else "v%g" % speed[0]
    return "%s_d%g_%g_%g_%s_s%d" % (test, size, bond[0], bond[1], s, seed)


def line_of(name, r):
    return {"run": name, "peak_load": r.get("peak_load"), "peak_reached": r.get("peak_reached"),
            "loading_rate": r.get("loading_rate", {}), "steps": r.get("steps"),
            "wall_seconds": r.get("wall_seconds")}


def run_keyed(a, runs):
    """runs: [(key, spec)] -> {key: result}."""
    return run_all(a, [(k, name_of(*k), spec) for k, spec in runs], line_of)


def peak(r):
    return r["peak_load"] if r.get("peak_reached") else float("nan")


def mean_peak(results, keys):
    values = [peak(results[k]) for k in keys]
    return sum(values) / len(values)


def homogeneity(a):
    scales = [float(s) for s in a.scales.split(",")]
    speeds = [(a.fixed, 0), ("auto", a.auto_transits)]
    runs = []
    for test in ("uct", "btt"):
        for speed in speeds:
            for s in scales:
                bond = (s, s * a.ratio)
                for seed in range(1, a.seeds + 1):
                    k = (test, a.size, bond, speed, seed)
                    runs.append((k, job(test, a.size, bond, speed, a, seed)))
    results = run_keyed(a, runs)
    print("| test | speed | F_r0 | F_s0 | peak load | kinetic/bond energy | peak transits | p to next |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for test in ("uct", "btt"):
        for speed in speeds:
            label = "auto (%g transits)" % speed[1] if speed[0] == "auto" else "%g" % speed[0]
            loads = []
            for i, s in enumerate(scales):
                bond = (s, s * a.ratio)
                keys = [(test, a.size, bond, speed, seed) for seed in range(1, a.seeds + 1)]
                loads.append(mean_peak(results, keys))
                q = results[keys[0]].get("loading_rate", {})
                p = ""
                if i > 0:
                    p_prev = math.log(loads[i] / loads[i - 1]) / math.log(s / scales[i - 1])
                    p = "%.3f" % p_prev
                print("| %s | %s | %g | %g | %.4g | %s | %s | %s |" % (
                    test, label, bond[0], bond[1], loads[i], q.get("kinetic_energy_ratio"),
                    q.get("peak_transits"), p))
            whole = math.log(loads[-1] / loads[0]) / math.log(scales[-1] / scales[0])
            print("| %s | %s | whole range | | | | | %.3f |" % (test, label, whole))


def rate(a):
    bond = tuple(float(x) for x in a.bond.split(","))
    transits = [float(t) for t in a.transits.split(",")]
    speeds = [(a.fixed, 0)] + [("auto", t) for t in transits]
    runs = [((test, a.size, bond, speed, 1), job(test, a.size, bond, speed, a, 1))
            for test in ("uct", "btt") for speed in speeds]
    results = run_keyed(a, runs)
    print("| test | speed | platen speed | peak load | change | kinetic/bond energy | peak transits"
          " | steps | wall s |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for test in ("uct", "btt"):
        previous = None
        for speed in speeds:
            r = results[(test, a.size, bond, speed, 1)]
            q = r.get("loading_rate", {})
            load = peak(r)
            change = ""
            if speed[0] == "auto" and previous is not None:
                change = "%+.2f%%" % (100 * (load / previous - 1))
            if speed[0] == "auto":
                previous = load
            label = "auto %g" % speed[1] if speed[0] == "auto" else "fixed"
            print("| %s | %s | %.4g | %.5g | %s | %.3g | %.1f | %d | %.1f |" % (
                test, label, q.get("platen_velocity", float("nan")), load, change,
                q.get("kinetic_energy_ratio") or float("nan"), q.get("peak_transits") or 0,
                r.get("steps", 0), r.get("wall_seconds", 0)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mode", choices=["homogeneity", "rate"])
    add_run_options(ap, ROOT, "auto_speed", size=10, auto_transits=20, slow_factor=1.0)
    ap.add_argument("--scales", default="2,20,200")
    ap.add_argument("--ratio", type=float, default=1.0)
    ap.add_argument("--bond", default="64,64")
    ap.add_argument("--transits", default="2.5,5,10,20,40")
    ap.add_argument("--fixed", type=float, default=0.05)
    ap.add_argument("--max-strain", type=float, default=0.2)
    a = ap.parse_args()
    homogeneity(a) if a.mode == "homogeneity" else rate(a)


if __name__ == "__main__":
    main()
