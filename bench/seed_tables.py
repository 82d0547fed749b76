#!/usr/bin/env python3
"""The seed paper's Tables 2 and 3 at full size (issue 16 item 4, docs/specimens.md).

Runs the paper's specimens (UCT cylinder D 49, H 139; Brazilian disc D 49, t 24.5; R 1, K_r 8000,
nu 0.2, dt 0.001 s, platen speed 0.02 m/s) at the tables' (F_r0, F_s0) points, twice:
  - "seed": as the paper set it up: FCC, full disc between flat platens, the lattice cut whose
    particle count is the paper's 44,394 (seeded placement --seed-cut, found by counting cuts);
  - "default": rockcal's default specimen (seeded FCC, flattened disc of 2 alpha = 30 degrees),
    --realisations seeds, mean and standard error;
and prints each run against the paper's value, and UCS/BTS of both set-ups (the paper's load ratio
for its t = D/2 disc).

  bench/seed_tables.py [--build build] [--out runs/seed_tables] [--realisations 3] [--jobs 2]
      [--uct 64/64,64/128] [--btt 64/64,32/64,64/128] [--seed-cut 6]

On demand only: a full-size UCT is about 2.6e9 particle-steps (several CPU minutes).
"""
import argparse
import concurrent.futures
import json
import math
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from specimen_convergence import MATERIAL, ROOT, engine_digest, run  # noqa: E402

PAPER_UCT = {(4.8, 14.4): 60696, (4.8, 24): 140000, (8, 14.4): 45758, (8, 20): 75475,
             (8, 32): 113798, (14.4, 4.8): 18000, (14.4, 6.4): 21432, (14.4, 9.6): 29040,
             (16, 24): 55195, (64, 64): 164422, (64, 128): 236588}
PAPER_BTT = {(4.8, 24): 6337, (6.4, 14.4): 5000, (32, 64): 14025, (32, 96): 14101,
             (64, 64): 17814, (64, 96): 22337, (64, 128): 27161}


def spec(test, point, setup, seed):
    sample = {"diameter": 49, "radius": 1.0, "packing": "fcc", "seed": seed}
    loading = {"platen_velocity": 0.02, "dt": 0.001}
    if test == "uct":
        sample["height"] = 139
    else:
        sample["thickness"] = 24.5
        loading["btt_geometry"] = "flat_platens" if setup == "seed" else "flattened"
    return {"test": test, "sample": sample, "material": MATERIAL,
            "bond": {"fr0": point[0], "fs0": point[1]}, "loading": loading}


def points(text):
    return [tuple(float(v) for v in p.split("/")) for p in text.split(",")]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "runs", "seed_tables"))
    ap.add_argument("--realisations", type=int, default=3)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--uct", default="64/64,64/128")
    ap.add_argument("--btt", default="64/64,32/64,64/128")
    ap.add_argument("--seed-cut", type=int, default=6)
    a = ap.parse_args()
    engine = os.path.join(a.build, "engine", "rockcal-dem")
    digest = engine_digest(engine)
    plan = []
    for test, pts in (("uct", points(a.uct)), ("btt", points(a.btt))):
        for p in pts:
            plan.append((test, p, "seed", a.seed_cut))
            for k in range(a.realisations):
                # The UCT is the same specimen in both set-ups: its default ensemble starts at the
                # seed cut, so the seed run is the ensemble's first realisation.
                plan.append((test, p, "default", a.seed_cut + k))
    os.makedirs(a.out, exist_ok=True)
    results = {}
    # Entries with the same spec (the UCT's seed run is its default ensemble's first) run once.
    unique = {}
    for p in plan:
        unique.setdefault(json.dumps(spec(*p[:3], p[3]), sort_keys=True), []).append(p)
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        futures = {pool.submit(run, engine, digest, a.out, json.loads(k)): ps
                   for k, ps in unique.items()}
        for k, f in enumerate(concurrent.futures.as_completed(futures), 1):
            for p in futures[f]:
                results[p] = f.result()
            print(f"\r{k}/{len(unique)} runs", end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)

    def ensemble(test, p, key="peak_load"):
        rs = [results[(test, p, "default", a.seed_cut + k)] for k in range(a.realisations)]
        ok = [r[key] for r in rs if r["peak_reached"]]
        mean = statistics.fmean(ok) if ok else float("nan")
        se = statistics.stdev(ok) / math.sqrt(len(ok)) if len(ok) > 1 else float("nan")
        return mean, se, len(ok), len(rs), statistics.fmean(r["cpu_seconds"] for r in rs)

    print("| test | F_r0/F_s0 | paper | seed set-up (particles) | vs paper | default mean +- se "
          "(n) | vs paper | CPU s/run |")
    print("|---|---|---|---|---|---|---|---|")
    for test, pts, paper in (("uct", points(a.uct), PAPER_UCT), ("btt", points(a.btt), PAPER_BTT)):
        for p in pts:
            r = results[(test, p, "seed", a.seed_cut)]
            ref = paper.get(p)
            seed_text = (f"{r['peak_load']:.0f} ({r['particles']})" if r["peak_reached"] else
                         f"no peak: {r['no_peak_reason']}")
            dev = f"{100 * (r['peak_load'] / ref - 1):+.1f}%" if ref and r["peak_reached"] else ""
            mean, se, n, total, cpu = ensemble(test, p)
            dev2 = f"{100 * (mean / ref - 1):+.1f}%" if ref and n else ""
            print(f"| {test} | {p[0]:g}/{p[1]:g} | {ref or ''} | {seed_text} | {dev} | "
                  f"{mean:.0f} +- {se:.0f} ({n}/{total}) | {dev2} | {cpu:.0f} |")
    # The ratio as the paper compares it: UCS / BTS, which is the load ratio for a full disc of
    # t = D/2; a flattened disc's load is converted through its own strength formula.
    for p in points(a.uct):
        if p not in points(a.btt):
            continue
        seed_u, seed_b = results[("uct", p, "seed", a.seed_cut)], results[("btt", p, "seed", a.seed_cut)]
        if not (seed_u["peak_reached"] and seed_b["peak_reached"]):
            print(f"\nUCS/BTS at {p[0]:g}/{p[1]:g}: no ratio (a seed set-up run has no peak)")
            continue
        s_u, s_b = seed_u["strength"], seed_b["strength"]
        u, su, *_ = ensemble("uct", p, "strength")
        b, sb, *_ = ensemble("btt", p, "strength")
        ratio = u / b
        ratio_se = ratio * math.hypot(su / u, sb / b)
        paper = PAPER_UCT[p] / PAPER_BTT[p] if p in PAPER_UCT and p in PAPER_BTT else float("nan")
        print(f"\nUCS/BTS at {p[0]:g}/{p[1]:g}: paper {paper:.2f}, seed set-up {s_u / s_b:.2f}, "
              f"default {ratio:.2f} +- {ratio_se:.2f} (lab 6.0)")

if __name__ == "__main__":
    main()
