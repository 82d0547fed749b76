#!/usr/bin/env python3
"""Coverage of the bayes calibration's credible region on real-engine twins (docs/inference.md).

Each twin: a truth (F_r0, F_s0) drawn log-uniformly inside the main job's box (seeded by the twin's
number; redrawn while F_s0/F_r0 exceeds --max-ratio, where the specimen has no UCT peak, or while
the lab runs reach no peak: a lab rock has one), the "lab" = the engine's own mean over --lab-packings packings at the truth (a sweep with
realisations; seeds far from the calibration's), stated to the standard error those packings give
(at least 2%); then the main job's request (examples/calibrate_seed_lab.json, its specimen and
budget) with those model-unit targets alone (its E and nu targets dropped: the twin's lab runs at
the template's stiffness). Recorded: whether the truth lies in the 90% region (its
cells on the log grid), the intervals, the verdict, runs and wall time.

`--strategy auto --realisations auto` runs the same twins (the same lab, from the same seeds) with
the previous driver instead, for the runs side by side: its "inside" is the truth within the
consistent set's F_r0 and F_s0 ranges.

Resumes: rows already in --out (one JSON object per line) are kept and their twins skipped, so it
may be run in parts; commit the file as it grows.

  bench/bayes_twins.py [--build build] [--twins 10] [--out bench/results/bayes_twins_d20_auto.jsonl]
                       [--strategy bayes|auto|ratio_scale|direct_2d] [--realisations auto|N]
On demand only (3-5 minutes a twin on 2 idle cores); it builds nothing.
"""
import argparse
import json
import math
import os
import random
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from rockcal_service import append_row, call, finish, load_rows, start_server  # noqa: E402


def in_region(post, fr0, fs0):
    # The grid spans where the posterior's mass lies (zoomed inside the bounds): a truth outside
    # it is outside the region.
    g = post["region"]["grid"]
    n = g["cells"]
    cell = lambda v, r: int(math.floor(math.log(v / r[0]) / math.log(r[1] / r[0]) * n))
    i, j = cell(fr0, g["fr0"]), cell(fs0, g["fs0"])
    if not (0 <= i < n and 0 <= j < n):
        return False
    return any(s[0] == j and s[1] <= i <= s[2] for s in post["region"]["spans"])


def lab_at(url, job, truth, twin, packings):
    """The engine's mean over `packings` packings at the truth, per test with at least two peaks:
    {test: (geometric mean, its relative standard error, at least 2%)}."""
    sweep = call(f"{url}/api/v1/campaigns", {
        "kind": "sweep", "name": f"bayes twin {twin}: lab", "tests": ["uct", "btt"],
        "job": job, "points": [truth], "realisations": packings})
    rows = call(f"{url}/api/v1/campaigns/{finish(url, sweep['id'])['id']}/results")["results"]
    lab = {}
    for test in ("uct", "btt"):
        logs = [math.log(r["peak_load"]) for r in rows if r["test"] == test and r.get("peak_load")]
        if len(logs) < 2:
            break
        m = sum(logs) / len(logs)
        sd = math.sqrt(sum((x - m) ** 2 for x in logs) / (len(logs) - 1))
        lab[test] = (math.exp(m), max(0.02, sd / math.sqrt(len(logs))))
    return lab


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--twins", type=int, default=10)
    ap.add_argument("--lab-packings", type=int, default=4)
    ap.add_argument("--max-ratio", type=float, default=3.0,
                    help="largest F_s0/F_r0 of a truth: above about 3.3 the main job's specimen "
                         "reaches no UCT peak at the auto speed")
    ap.add_argument("--request", default=os.path.join(ROOT, "examples", "calibrate_seed_lab.json"))
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "bayes_twins_d20_auto.jsonl"))
    ap.add_argument("--strategy", default="bayes")
    ap.add_argument("--realisations", default=None, help="the previous driver's packings an evaluation")
    a = ap.parse_args()
    os.makedirs(os.path.dirname(a.out), exist_ok=True)
    done = load_rows(a.out, "twin")
    base = json.load(open(a.request))
    work = tempfile.mkdtemp(prefix="rockcal-bayes-twins.")
    proc, url = start_server(a.build, work)
    try:
        for twin in range(1, a.twins + 1):
            if twin in done:
                continue
            rng = random.Random(twin)
            t0 = time.time()
            job = json.loads(json.dumps(base["job"]))
            job["sample"]["seed"] = 100000 + 100 * twin  # the lab's packings, not the search's
            # A lab rock has a peak: a truth whose lab runs reach none is drawn again (kept in
            # "no_peak_truths"), as is one beyond --max-ratio, where the specimen never peaks.
            no_peak, lab = [], {}
            while len(no_peak) < 5:
                truth = [math.exp(rng.uniform(math.log(15), math.log(80))),
                         math.exp(rng.uniform(math.log(30), math.log(160)))]
                if truth[1] > a.max_ratio * truth[0]:
                    continue
                lab = lab_at(url, job, truth, twin, a.lab_packings)
                if len(lab) == 2:
                    break
                no_peak.append(truth)
            if len(lab) < 2:
                row = {"twin": twin, "no_peak_truths": no_peak, "error": "the lab runs had no peak"}
            else:
                req = json.loads(json.dumps(base))
                req["name"] = f"bayes twin {twin}"
                req["targets"] = {"uct": {"peak_load": lab["uct"][0]}, "btt": {"peak_load": lab["btt"][0]}}
                if a.strategy == "bayes":
                    req.setdefault("inference", {})["lab_uncertainty"] = {"uct": lab["uct"][1], "btt": lab["btt"][1]}
                else:
                    req["strategy"] = a.strategy
                    req.pop("inference", None)
                    if a.realisations:
                        req["realisations"] = a.realisations if a.realisations == "auto" else int(a.realisations)
                cal = finish(url, call(f"{url}/api/v1/campaigns", req)["id"])
                s = cal.get("summary") or {}
                post = s.get("posterior")
                row = {"twin": twin, "truth": truth, "lab_sd": [lab["uct"][1], lab["btt"][1]],
                       "no_peak_truths": no_peak,
                       "verdict": s.get("verdict"), "wall_seconds": round(time.time() - t0, 1),
                       "platen_velocity": base["job"].get("loading", {}).get("platen_velocity"),
                       "strategy": a.strategy, "jobs": (cal.get("progress") or {}).get("total"),
                       "stop_reason": s.get("stop_reason")}
                best = s.get("best") or {}
                if a.strategy != "bayes":
                    cons = s.get("consistent") or {}
                    row.update({"unique": s.get("unique"), "fr0": cons.get("fr0"), "fs0": cons.get("fs0"),
                                "best": {"fr0": best.get("fr0"), "fs0": best.get("fs0"),
                                         "uct": (best.get("uct") or {}).get("relative_error"),
                                         "btt": (best.get("btt") or {}).get("relative_error")}})
                    if cons.get("fr0") and cons.get("fs0"):
                        row["inside"] = (cons["fr0"][0] <= truth[0] <= cons["fr0"][1]
                                         and cons["fs0"][0] <= truth[1] <= cons["fs0"][1])
                elif post:
                    row.update({"inside": in_region(post, *truth), "fr0": post["fr0"], "fs0": post["fs0"],
                                "estimate": post["estimate"], "runs": post["runs"], "unique": post["unique"],
                                # what the verdict rests on: the prediction's sd and the checks
                                "predicted": {k: {"relative_error": post[k].get("relative_error"),
                                                  "emulator_sd": post[k].get("emulator_sd"),
                                                  "check": post[k].get("check")}
                                              for k in ("uct", "btt")}})
            done[twin] = row
            append_row(a.out, row)
    finally:
        proc.terminate()
        proc.wait()
    rows = [r for r in done.values() if "inside" in r]
    if rows:
        k = sum(r["inside"] for r in rows)
        print(f"coverage: truth inside the 90% region in {k} of {len(rows)} twins")


if __name__ == "__main__":
    main()
