#!/usr/bin/env python3
"""Reach: which UCS/BTS and UCS/E the default specimen reaches (docs/reach.md).

For each interaction range factor in --factors (bonds join pairs within factor x (R_i + R_j);
1 = touching neighbours only, the default model) and each strength ratio s = F_s0 / F_r0 in
--ratios, runs the UCT (H = 2D) and the flattened-disc BTT (t = D/2) of the default specimen at
D/R --size with the auto platen speed, at the bond strengths F_r0 = F / sqrt(s), F_s0 = F sqrt(s)
(F = --strength), on --seeds seeds. With the auto speed a bond-controlled peak is homogeneous of
degree 1 in the strengths (docs/loading-rate.md), so the load ratio depends on s and the factor
only, and UCS/E scales with F: the map at one F gives the reach at every F. A peak that came after
the bond-controlled window (loading_rate.late_peak) is counted and marked, as is a run without a
peak. Per range, an elastic test of the same cylinder (bonds unbroken) gives the specimen's E and
nu at the material's K_s/K_r (--nu sets it by eq. 3, as a calibration's start does).

  bench/reach_map.py [--build build] [--out runs/reach] [--size 20] [--strength 20]
      [--ratios 0.25,0.5,1,2,4,8] [--factors 1,1.5,1.8] [--seeds 1] [--jobs 1]
      [--packing fcc|random] [--radius-ratio 1.5] [--nu 0.2] [--stiffness-exponent 0]
      [--follow-transits 0] [--effect NAME:PARAM=X ...]
      [--auto-transits 10] [--slow-factor 0.25] [--log FILE]

Prints a markdown table (means over the seeds with a peak): UCT and BTT peak loads, the load
ratio, UCS/BTS, E, UCS/E, bonds per particle and the count of late or missing peaks; then per
range the elastic test's E and nu. --log appends one JSON line per finished run.
"""
import argparse
import math
import os
import statistics
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench", "effects"))
from engine_runs import add_run_options, parse_effect, run_all  # noqa: E402


def job(test, a, s, factor, seed):
    sample = {"diameter": a.size, "radius": 1.0, "packing": a.packing, "seed": seed}
    if a.packing == "random":
        sample["radius_ratio"] = a.radius_ratio
    if test in ("uct", "elastic"):
        sample["height"] = 2 * a.size
    spec = {"test": test, "sample": sample,
            "material": {"density": 1.0, "kr": 8000, "nu": a.nu},
            "bond": {"fr0": a.strength / math.sqrt(s), "fs0": a.strength * math.sqrt(s)},
            "contact": {"friction": 0.6},
            "loading": {"platen_velocity": "auto", "auto_transits": a.auto_transits,
                        "past_window": a.past_window,
                        "dt": "auto", "slow_factor": a.slow_factor, "max_strain": 0.1},
            "damping": {"local": 0.7}}
    if a.follow_transits:  # the engine refuses 0: off is the field left out
        spec["loading"]["follow_transits"] = a.follow_transits
    effects = {}
    if factor != 1.0:
        effects["interaction_range"] = {"factor": factor,
                                        "stiffness_exponent": a.stiffness_exponent}
    for text in a.effect:
        effects.update(parse_effect(text)[1])
    if effects:
        spec["effects"] = effects
    return spec


def line_of(name, r):
    q = r.get("loading_rate") or {}
    return {"run": name, "peak_reached": r.get("peak_reached"), "peak_load": r.get("peak_load"),
            "strength": r.get("strength"), "youngs_modulus": r.get("youngs_modulus"),
            "poisson_ratio": r.get("poisson_ratio"),
            "late_peak": q.get("late_peak"), "peak_transits": q.get("peak_transits"),
            "particles": r.get("particles"), "bonds": r.get("bonds"), "steps": r.get("steps"),
            "wall_seconds": r.get("wall_seconds")}


def main():
    ap = argparse.ArgumentParser()
    add_run_options(ap, ROOT, "reach", size=20, auto_transits=10, slow_factor=0.25)
    ap.add_argument("--strength", type=float, default=20)
    ap.add_argument("--ratios", default="0.25,0.5,1,2,4,8")
    ap.add_argument("--factors", default="1,1.5,1.8")
    ap.add_argument("--packing", choices=["fcc", "random"], default="fcc")
    ap.add_argument("--radius-ratio", type=float, default=1.5)
    ap.add_argument("--nu", type=float, default=0.2)
    ap.add_argument("--stiffness-exponent", type=float, default=0.0,
                    help="n: bonds beyond touching get stiffnesses x ((R_i + R_j) / L)^n")
    ap.add_argument("--follow-transits", type=float, default=0.0,
                    help="loading.follow_transits (0: off), as the rock benchmark's templates use 100")
    ap.add_argument("--effect", action="append", default=[],
                    help="another engine effect on every run, NAME:PARAM=X;PARAM=Y (repeatable)")
    a = ap.parse_args()
    ratios = [float(x) for x in a.ratios.split(",")]
    factors = [float(x) for x in a.factors.split(",")]
    runs = []
    for f in factors:
        for s in ratios:
            for test in ("uct", "btt"):
                for seed in range(1, a.seeds + 1):
                    name = "%s_d%g_F%g_s%g_range%g_seed%d" % (test, a.size, a.strength, s, f, seed)
                    runs.append(((f, s, test, seed), name, job(test, a, s, f, seed)))
        for seed in range(1, a.seeds + 1):
            name = "elastic_d%g_range%g_seed%d" % (a.size, f, seed)
            runs.append(((f, None, "elastic", seed), name, job("elastic", a, 1.0, f, seed)))
    if a.packing != "fcc" or a.nu != 0.2 or a.stiffness_exponent or a.effect or a.follow_transits:
        # the FCC map's run names stay those of its cache
        tag = "_%s%s_nu%g" % (a.packing, "_rr%g" % a.radius_ratio if a.packing == "random" else "",
                              a.nu)
        if a.stiffness_exponent:
            tag += "_n%g" % a.stiffness_exponent
        if a.follow_transits:
            tag += "_follow%g" % a.follow_transits
        for text in a.effect:
            tag += "_" + text.replace(":", "_").replace(";", "_").replace("=", "")
        runs = [(key, name + tag, spec) for key, name, spec in runs]
    results = run_all(a, runs, line_of)

    def mean_of(f, s, test, field):
        values = [results[(f, s, test, seed)][field] for seed in range(1, a.seeds + 1)
                  if results[(f, s, test, seed)].get("peak_reached")
                  and results[(f, s, test, seed)].get(field) is not None]
        return statistics.mean(values) if values else float("nan")

    def unusual(f, s, test):
        late = missing = 0
        for seed in range(1, a.seeds + 1):
            r = results[(f, s, test, seed)]
            if not r.get("peak_reached"):
                missing += 1
            elif (r.get("loading_rate") or {}).get("late_peak"):
                late += 1
        return late, missing

    print("| range factor | F_s0/F_r0 | UCT load | BTT load | load ratio | UCS/BTS | E | UCS/E |"
          " bonds/particle | late peaks (UCT, BTT) | no peak (UCT, BTT) |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for f in factors:
        for s in ratios:
            uct, btt = mean_of(f, s, "uct", "peak_load"), mean_of(f, s, "btt", "peak_load")
            ucs, bts = mean_of(f, s, "uct", "strength"), mean_of(f, s, "btt", "strength")
            e = mean_of(f, s, "uct", "youngs_modulus")
            r1 = results[(f, s, "uct", 1)]
            per = 2.0 * r1.get("bonds", 0) / max(r1.get("particles", 1), 1)
            lu, mu = unusual(f, s, "uct")
            lb, mb = unusual(f, s, "btt")
            print("| %g | %g | %.4g | %.4g | %.3g | %.3g | %.4g | %.3g | %.2f | %d, %d | %d, %d |" % (
                f, s, uct, btt, uct / btt, ucs / bts, e, ucs / e, per, lu, lb, mu, mb))
    print()
    print("| range factor | elastic E | elastic nu (material nu %g) |" % a.nu)
    print("| --- | --- | --- |")
    for f in factors:
        es = [results[(f, None, "elastic", seed)] for seed in range(1, a.seeds + 1)]
        e = [r["youngs_modulus"] for r in es if r.get("youngs_modulus") is not None]
        nu = [r["poisson_ratio"] for r in es if r.get("poisson_ratio") is not None]
        print("| %g | %.4g | %.3f |" % (f, statistics.mean(e) if e else float("nan"),
                                         statistics.mean(nu) if nu else float("nan")))


if __name__ == "__main__":
    main()
