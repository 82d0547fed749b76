#!/usr/bin/env python3
"""Specimen convergence study (issue 16, docs/specimens.md).

For each packing (fcc, random), test (uct, btt) and BTT loading geometry, runs the engine at
particle resolutions D/R in --sizes, each at --realisations seeds and at diameters D, 1.01 D and
1.02 D (the 1% and 2% steps), and reports per (packing, test, geometry, D/R):
  mean, CV and standard error of UCS or BTS (and E for the UCT), the mean CPU time per run (one
  core; wall time on a loaded machine says nothing), how far
  the ensemble mean moves for the 1% and 2% diameter steps (and how many standard errors that is),
  the share of BTT runs that split from the centre, and every run that ended without a peak.

  bench/specimen_convergence.py [--build build] [--out runs/specimens] [--sizes 10,15,20,30]
      [--packings fcc,random] [--tests uct,btt] [--geometries curved_jaws,flattened:30,flat_platens]
      [--realisations 5] [--steps 0,0.01,0.02] [--jobs 2] [--material JSON] [--bond fr0,fs0]

Runs are cached in OUT/runs/ by their spec and the engine binary's digest (a rebuilt engine runs
everything again), so widening a study reuses what exists. Writes OUT/runs.csv (one row per run) and OUT/summary.md. On demand only: the default
study is several hundred engine runs (about an hour on 2 cores, docs/specimens.md).
"""
import argparse
import concurrent.futures
import csv
import hashlib
import json
import math
import os
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# The seed paper's model material (model units, docs/calibration.md): K_r 8000 N/m, nu 0.2, unit
# density and radius, F_r0 = F_s0 = 64 N; dt 0.001 s as the paper.
MATERIAL = {"density": 1.0, "kr": 8000, "nu": 0.2}
UCT_ASPECT = 2.0  # H / D of the study's cylinders (ISRM asks 2.5-3; 2 keeps the study affordable)
VELOCITY = 0.02   # m/s per platen (model units), docs/loading-rate.md


def job(packing, test, geometry, d_over_r, step, seed, bond, velocity):
    d = d_over_r * (1.0 + step)
    sample = {"diameter": round(d, 6), "packing": packing, "radius": 1.0, "seed": seed}
    if test == "uct":
        sample["height"] = round(UCT_ASPECT * d, 6)
    loading = {"platen_velocity": velocity, "dt": 0.001}
    if test == "btt":  # "flattened:30" is a flattened disc of loading angle 30 degrees
        name, _, angle = geometry.partition(":")
        loading["btt_geometry"] = name
        if angle:
            loading["flat_angle_deg"] = float(angle)
    return {"test": test, "sample": sample, "material": MATERIAL,
            "bond": {"fr0": bond[0], "fs0": bond[1]}, "loading": loading}


def engine_digest(engine):
    with open(engine, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def run(engine, digest, out, spec):
    text = json.dumps(spec, sort_keys=True)
    key = hashlib.sha256((digest + text).encode()).hexdigest()[:16]
    d = os.path.join(out, "runs", key)
    result = os.path.join(d, "result.json")
    refused = os.path.join(d, "refused.txt")
    if os.path.exists(refused):  # the engine refused the specimen (exit 1): a finding, not a crash
        with open(refused) as f:
            return {"error": f.read().strip()}
    if not os.path.exists(result):
        os.makedirs(d, exist_ok=True)
        with open(os.path.join(d, "job.json"), "w") as f:
            f.write(text)
        with open(os.path.join(d, "stderr.log"), "w") as err:
            p = subprocess.Popen([engine, "run", os.path.join(d, "job.json"), "--out", d],
                                 stdout=subprocess.DEVNULL, stderr=err)
            # CPU time, not wall time: the figure that stays true on a loaded machine.
            _, status, usage = os.wait4(p.pid, 0)
        code = os.waitstatus_to_exitcode(status)
        if code == 1:
            with open(os.path.join(d, "stderr.log")) as f:
                lines = [l for l in f.read().splitlines() if l.strip()]
            with open(refused, "w") as f:
                f.write((lines[-1] if lines else "exit 1") + "\n")
            return run(engine, digest, out, spec)
        if code != 0:
            raise RuntimeError(f"{d}: exit {os.waitstatus_to_exitcode(status)} (see stderr.log)")
        with open(os.path.join(d, "cpu_seconds"), "w") as f:
            f.write(f"{usage.ru_utime + usage.ru_stime}\n")
    with open(result) as f:
        r = json.load(f)
    with open(os.path.join(d, "cpu_seconds")) as f:
        r["cpu_seconds"] = float(f.read())
    return r


def row(spec, geometry, d_over_r, step, r):
    if "error" in r:  # no specimen at all: counted with the runs without a peak
        r = {"particles": 0, "peak_reached": False, "no_peak_reason": r["error"],
             "peak_load": float("nan"), "strength": float("nan"), "wall_seconds": 0.0,
             "cpu_seconds": 0.0, "broken_bonds_at_peak": 0}
    btt = r.get("btt", {})
    first = btt.get("first_interior_breaks", {})
    return {
        "packing": spec["sample"]["packing"], "test": spec["test"], "geometry": geometry,
        "d_over_r": d_over_r, "step": step, "seed": spec["sample"]["seed"],
        "diameter": spec["sample"]["diameter"], "particles": r["particles"],
        "peak_reached": r["peak_reached"], "no_peak_reason": r.get("no_peak_reason", ""),
        "peak_load": r["peak_load"], "strength": r["strength"],
        "youngs_modulus": r.get("youngs_modulus"), "wall_seconds": r["wall_seconds"],
        "cpu_seconds": r["cpu_seconds"],
        "broken_at_peak": r["broken_bonds_at_peak"],
        "centre_split": btt.get("centre_split", ""),
        "first_median_r_over_R": first.get("median_r_over_R", ""),
        "loaded_band_fraction": btt.get("loaded_band_fraction", ""),
    }


def stats(values):
    n = len(values)
    if n == 0:
        return None
    mean = statistics.fmean(values)
    sd = statistics.stdev(values) if n > 1 else float("nan")
    return {"n": n, "mean": mean, "sd": sd, "se": sd / math.sqrt(n), "cv": sd / mean}


def summarise(rows, steps):
    groups = {}
    for r in rows:
        groups.setdefault((r["packing"], r["test"], r["geometry"], r["d_over_r"]), []).append(r)
    lines = ["| packing | test | geometry | D/R | particles | n | mean strength | CV | se | E mean "
             "(CV) | CPU s/run | 1% step | 2% step | centre splits | no peak |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for (packing, test, geometry, dr), rs in sorted(groups.items()):
        by_step = {s: [r for r in rs if r["step"] == s] for s in steps}
        base = [r for r in by_step[steps[0]] if r["peak_reached"]]
        s0 = stats([r["strength"] for r in base])
        if s0 is None:
            continue
        e = stats([r["youngs_modulus"] for r in base if r["youngs_modulus"]])
        moves = []
        for s in steps[1:]:
            st = stats([r["strength"] for r in by_step[s] if r["peak_reached"]])
            if st is None:
                moves.append("-")
                continue
            delta = st["mean"] / s0["mean"] - 1.0
            se = math.hypot(s0["se"], st["se"]) / s0["mean"]
            moves.append(f"{100 * delta:+.1f}% ({abs(delta) / se:.1f} se)" if se > 0 else
                         f"{100 * delta:+.1f}%")
        while len(moves) < 2:
            moves.append("")
        splits = [r for r in rs if r["test"] == "btt" and r["peak_reached"]]
        split_text = (f"{sum(1 for r in splits if r['centre_split'])}/{len(splits)}"
                      if splits else "")
        no_peak = sum(1 for r in rs if not r["peak_reached"])
        e_text = f"{e['mean']:.4g} ({100 * e['cv']:.1f}%)" if e else ""
        lines.append(
            f"| {packing} | {test} | {geometry if test == 'btt' else ''} | {dr:g} | "
            f"{statistics.fmean(r['particles'] for r in base):.0f} | {s0['n']} | "
            f"{s0['mean']:.4g} | {100 * s0['cv']:.1f}% | {s0['se']:.3g} | {e_text} | "
            f"{statistics.fmean(r['cpu_seconds'] for r in rs):.1f} | {' | '.join(moves)} | "
            f"{split_text} | {no_peak}/{len(rs)} |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "runs", "specimens"))
    ap.add_argument("--sizes", default="10,15,20,30")
    ap.add_argument("--packings", default="fcc,random")
    ap.add_argument("--tests", default="uct,btt")
    ap.add_argument("--geometries", default="curved_jaws,flattened,flat_platens")
    ap.add_argument("--realisations", type=int, default=5)
    ap.add_argument("--steps", default="0,0.01,0.02")
    ap.add_argument("--bond", default="64,64")
    ap.add_argument("--velocity", type=float, default=VELOCITY)
    ap.add_argument("--jobs", type=int, default=2)
    a = ap.parse_args()
    engine = os.path.join(a.build, "engine", "rockcal-dem")
    sizes = [float(x) for x in a.sizes.split(",")]
    steps = [float(x) for x in a.steps.split(",")]
    bond = [float(x) for x in a.bond.split(",")]
    plan = []
    for packing in a.packings.split(","):
        for test in a.tests.split(","):
            for geometry in (a.geometries.split(",") if test == "btt" else ["-"]):
                for dr in sizes:
                    for step in steps:
                        for seed in range(1, a.realisations + 1):
                            plan.append((job(packing, test, geometry, dr, step, seed, bond,
                                             a.velocity), geometry, dr, step))
    os.makedirs(a.out, exist_ok=True)
    rows = []
    digest = engine_digest(engine)
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        futures = {pool.submit(run, engine, digest, a.out, p[0]): p for p in plan}
        for k, f in enumerate(concurrent.futures.as_completed(futures), 1):
            spec, geometry, dr, step = futures[f]
            rows.append(row(spec, geometry, dr, step, f.result()))
            print(f"\r{k}/{len(plan)} runs", end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)
    rows.sort(key=lambda r: (r["packing"], r["test"], r["geometry"], r["d_over_r"], r["step"],
                             r["seed"]))
    with open(os.path.join(a.out, "runs.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    table = summarise(rows, steps)
    with open(os.path.join(a.out, "summary.md"), "w") as f:
        f.write(table)
    print(table)


if __name__ == "__main__":
    main()
