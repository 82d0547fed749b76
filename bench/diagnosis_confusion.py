#!/usr/bin/env python3
"""Confusion matrix of the gap diagnosis on synthetic twins (issue 6, docs/diagnosis.md).

For every engine effect and the null case, makes twins with `rockcal twin` (the effect hidden at a
known value, a seeded truth and 2% lab noise), diagnoses each through one `rockcal serve` (so the
grid runs, which do not depend on the lab data, are run once and then come from the job store),
and prints the matrix: hidden effect x verdict, the top-1 identification rate, the null case's
false-positive rate, the median held-out gap closure G of the correct verdicts, and wall times.

Values: by default each effect at s = 0.5, 0.75 and 1 of its diagnosis walk (neutral -> strong,
docs/effects.md), seeds 1, 2, 3; the null case with seeds 1, 2, 3.

  bench/diagnosis_confusion.py [--build build] [--out DIR] [--effects a,b] [--twins 3] [--values x,y]
                               [--request examples/diagnose_twin.json] [--gap-budgets X]
                               [--min-evidence X] [--results F.jsonl] [--truth-seed T]

--truth-seed T: every twin hides the truth strengths of seed T (their packings and lab noise still
follow their own seeds), so their fits land near one node of the local design's lattice and the
twins after the first take its design runs from the job store.

Also printed: the evidence threshold (nats of held-out log predictive density over the base
model, verdict.evidence) that at most 10% of the null twins' best contenders exceed, to be set as
the request's "decision": {"min_evidence": ...} for that template; the same for the gap
(held-out rms in budgets, "gap_budgets", the report's gap test); and per
effect the share identified at each hidden value and its detection limit (the smallest value
identified in >= 80% of >= 5 twins; --twins 15 gives 5 per value). A twin the engine cannot make
(a specimen with no peak) is recorded and left out, not replaced.

On demand only (tens of minutes on 2 cores); it builds nothing. Writes DIR/results.json (one row
per twin, with the campaign summary's verdict, gap and candidates) and DIR/matrix.md.

Resumable: with --results FILE (one JSON line per twin, meant to be committed, e.g.
bench/results/diagnosis_matrix_d20.jsonl) every finished twin is appended as it ends, a twin
already in the file (same request name, effect, value, seed and resolution) is not run again, and
the matrix is written over every row of the file, so a long matrix runs in parts. Keep --out
between the parts: its job store answers the runs the twins share (the local design runs on a
lattice of the template, docs/diagnosis.md).
"""
import argparse
import json
import math
import os
import signal
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# s = 0.5, 0.75, 1 along each effect's walk (engine/effects, effect_value_at): the value the twin
# hides. Linear walks: neutral + s (strong - neutral); heterogeneity is linear in 1/m; rate in log.
VALUES = {
    "heterogeneity": [4.0, 2.667, 2.0],
    "packing": [1.5, 1.75, 2.0],
    "platen_friction": [0.25, 0.375, 0.5],
    "flaws": [0.075, 0.1125, 0.15],
    "rate": [2.828, 4.757, 8.0],
    "compression_coupling": [0.5, 0.25, 0.0],
    "post_break_friction": [0.325, 0.1875, 0.05],
    # In FCC no pair lies between 1 and sqrt(2) touching distances: below 1.414 nothing changes.
    "interaction_range": [1.45, 1.475, 1.5],
    "rolling_resistance": [0.15, 0.225, 0.3],
    "brazilian_flats": [20.0, 15.0, 10.0],
}


def get(url):
    with urllib.request.urlopen(url, timeout=60) as r:
        return json.load(r)


def start_server(build, work):
    port_file = os.path.join(work, "port")
    if os.path.exists(port_file):
        os.remove(port_file)  # a previous run's port
    log = open(os.path.join(work, "serve.log"), "w")
    proc = subprocess.Popen(
        [os.path.join(build, "api", "rockcal"), "serve", "--db", os.path.join(work, "bench.db"),
         "--listen", "127.0.0.1:0", "--port-file", port_file, "--workers", "2",
         "--ranks-per-job", "0", "--engine", os.path.join(build, "engine", "rockcal-dem"),
         "--max-jobs", "100000"],
        stdout=log, stderr=subprocess.STDOUT)
    for _ in range(300):
        if os.path.exists(port_file) and open(port_file).read().strip():
            return proc, "http://127.0.0.1:" + open(port_file).read().strip()
        time.sleep(0.1)
    proc.kill()
    sys.exit("diagnosis_confusion: the server did not start (see serve.log)")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=None)
    ap.add_argument("--effects", default=",".join(["none"] + list(VALUES)))
    ap.add_argument("--twins", type=int, default=3)
    ap.add_argument("--first-seed", type=int, default=1)
    ap.add_argument("--values", default=None,
                    help="comma-separated hidden values, cycled over each effect's twins "
                         "(default: the effect's s = 0.5, 0.75, 1 values above)")
    ap.add_argument("--resolution", type=float, default=1.0,
                    help="twins made by a model this many times finer (1: same-resolution twins)")
    ap.add_argument("--request", default=os.path.join(ROOT, "examples", "diagnose_twin.json"))
    ap.add_argument("--gap-budgets", type=float, default=None,
                    help="the request's decision.gap_budgets (e.g. the threshold a null run printed)")
    ap.add_argument("--min-evidence", type=float, default=None,
                    help="the request's decision.min_evidence (e.g. the threshold a null run printed)")
    ap.add_argument("--truth-seed", type=int, default=None,
                    help="every twin hides the truth of this seed (rockcal twin --truth-seed): "
                         "their packings and noise still follow their own seed, and they share "
                         "the design's runs")
    ap.add_argument("--results", default=None,
                    help="JSON-lines file of finished twins: appended to, and twins already in it "
                         "are skipped (resume); the matrix is over all its rows")
    ap.add_argument("--reuse-twins", action="store_true",
                    help="keep twin files already in --out (e.g. a copy of an earlier run's, with its job store)")
    a = ap.parse_args()
    work = a.out or tempfile.mkdtemp(prefix="rockcal-confusion.")
    os.makedirs(work, exist_ok=True)
    rockcal = os.path.join(a.build, "api", "rockcal")
    base_request = json.load(open(a.request))
    base_request.pop("dataset_file", None)
    if a.gap_budgets is not None:
        base_request.setdefault("decision", {})["gap_budgets"] = a.gap_budgets
    if a.min_evidence is not None:
        base_request.setdefault("decision", {})["min_evidence"] = a.min_evidence
    # The twins are made on the request's template, so that a larger template (--request with
    # another "job") gets twins of its own resolution.
    # A "bond" in the request's job is the twins' template bond (their truths are drawn around it);
    # the diagnosis sets its own, so the request is sent without one.
    template = os.path.join(work, "template.json")
    json.dump(base_request["job"], open(template, "w"), indent=1)
    base_request["job"] = {k: v for k, v in base_request["job"].items() if k != "bond"}
    request_name = os.path.basename(a.request)

    def key_of(r):
        return (r.get("request"), r["hidden"], r["value"], r["seed"], r["resolution"],
                r.get("truth_seed"))

    rows = []  # this part's
    done = []
    if a.results and os.path.exists(a.results):
        done = [json.loads(line) for line in open(a.results) if line.strip()]
    done_keys = {key_of(r) for r in done}

    def keep(row):
        row["request"] = request_name
        row["truth_seed"] = a.truth_seed
        rows.append(row)
        json.dump(rows, open(os.path.join(work, "results.json"), "w"), indent=1)
        if a.results:
            with open(a.results, "a") as f:
                f.write(json.dumps(row) + "\n")

    proc, url = start_server(a.build, work)
    engine = get(f"{url}/healthz").get("engine_version")
    t_all = time.time()
    try:
        for effect in a.effects.split(","):
            for k in range(a.twins):
                seed = a.first_seed + k
                name = (f"{effect}-{seed}" + (f"-x{a.resolution:g}" if a.resolution != 1 else "")
                        + (f"-t{a.truth_seed}" if a.truth_seed is not None else ""))
                twin = os.path.join(work, f"twin_{name}.json")
                cmd = [rockcal, "twin", "--effect", effect, "--seed", str(seed), "--out", twin,
                       "--job", template, "--engine", os.path.join(a.build, "engine", "rockcal-dem"),
                       "--resolution", str(a.resolution)]
                if a.truth_seed is not None:
                    cmd += ["--truth-seed", str(a.truth_seed)]
                value = None
                if effect != "none":
                    values = ([float(x) for x in a.values.split(",")] if a.values
                              else VALUES[effect])
                    value = values[k % len(values)]
                    cmd += ["--value", str(value)]
                if (request_name, effect, value, seed, a.resolution, a.truth_seed) in done_keys:
                    print(f"{name:26} in {a.results} already", flush=True)
                    continue
                t0 = time.time()
                truth = twin[:-len(".json")] + ".truth.json"
                if not (a.reuse_twins and os.path.exists(twin) and os.path.exists(truth)):
                    made = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                          text=True)
                    if made.returncode != 0:
                        # A twin the engine cannot make (a specimen with no peak) is recorded and
                        # left out of the matrix, never replaced by another seed.
                        why = (made.stderr.strip().splitlines() or ["(no message)"])[-1]
                        keep({"hidden": effect, "value": value, "seed": seed,
                              "resolution": a.resolution, "twin_error": why})
                        print(f"{name:26} twin could not be made: {why}", flush=True)
                        continue
                t_twin = time.time() - t0
                req = dict(base_request)
                req["name"] = f"confusion {name}"
                req["dataset_file"] = os.path.basename(twin)
                req_file = os.path.join(work, f"request_{name}.json")
                json.dump(req, open(req_file, "w"), indent=1)
                t0 = time.time()
                out = subprocess.run(
                    [rockcal, "diagnose", req_file, "--server", url, "--html",
                     os.path.join(work, f"report_{name}.html")],
                    check=True, capture_output=True, text=True).stdout
                t_diag = time.time() - t0
                cid = int(out.split("diagnosis campaign ", 1)[1].split()[0])
                c = get(f"{url}/api/v1/campaigns/{cid}")
                s = c["summary"]
                v = s.get("verdict", {})
                found = v.get("effect") or "none"
                row = {
                    "hidden": effect, "value": value, "seed": seed, "campaign": cid,
                    "resolution": a.resolution,
                    "verdict": found, "parameter": (v.get("parameter") or {}).get("value"),
                    "gap_closure": v.get("gap_closure"), "gap": v.get("gap"),
                    "gap_closure_beyond_noise": closure_beyond_noise(s),
                    # The best contender's evidence (nats over the base), named or not.
                    "evidence": v.get("evidence"), "undetermined": v.get("undetermined"),
                    "confidence": (v.get("confidence") or {}).get("level"),
                    "runner_up": (v.get("runner_up") or {}).get("effect"),
                    "ranking": [x.get("effect") for x in sorted(
                        s.get("candidates", [])[1:], key=lambda x: x.get("rank") or 99)],
                    "candidates_g": {x.get("effect"): (x.get("gap_closure") or {}).get("value")
                                     for x in s.get("candidates", [])[1:]},
                    "base_gap": s.get("gap"), "reason": v.get("reason"),
                    "twin_seconds": round(t_twin, 1), "diagnosis_seconds": round(t_diag, 1),
                    "jobs": c.get("progress", {}).get("total"), "engine": engine,
                }
                keep(row)
                print(f"{name:26} verdict {found:22} G {row['gap_closure']} "
                      f"conf {row['confidence']} twin {t_twin:.0f} s diagnosis {t_diag:.0f} s",
                      flush=True)
    finally:
        proc.send_signal(signal.SIGTERM)
        proc.wait(timeout=60)
    if a.results:
        rows = [r for r in done if r.get("request") == request_name
                and r.get("truth_seed") == a.truth_seed] + rows
    write_matrix(rows, work, time.time() - t_all)


def null_threshold(null_gaps, max_false_positive=0.10):
    """The smallest threshold that at most max_false_positive of the null twins' figures exceed
    (their gap in budgets, or their best contender's evidence in nats), i.e. the decision
    threshold calibrated on these nulls."""
    gaps = sorted(null_gaps, reverse=True)
    allowed = int(max_false_positive * len(gaps))  # nulls that may lie above the threshold
    return gaps[allowed] if allowed < len(gaps) else 0.0


# The walk fractions of VALUES: twin k of an effect hides VALUES[effect][k % 3], at s = 0.5, 0.75, 1.
WALK = [0.5, 0.75, 1.0]


def detection_limits(eff):
    """Per effect: the share of its twins identified at each hidden value, and its detection limit,
    the smallest value identified in >= 80% of its twins there (with >= 5 twins at that value for
    the limit to count; fewer are shown but not taken as a limit)."""
    lines = []
    for effect in dict.fromkeys(r["hidden"] for r in eff):
        per_value = []
        for i, value in enumerate(VALUES.get(effect, [])):
            twins = [r for r in eff if r["hidden"] == effect and r["value"] == value]
            if twins:
                hits = sum(1 for r in twins if r["verdict"] == effect)
                per_value.append((WALK[i], value, hits, len(twins)))
        limit = next((f"{v:g} (s = {w:g} of the walk from neutral to strong)" for w, v, h, n in per_value
                      if n >= 5 and h >= 0.8 * n), "none among the values tested")
        shown = ", ".join(f"{v:g}: {h}/{n}" for w, v, h, n in per_value)
        lines.append(f"- {effect}: identified {shown}; detection limit {limit}")
    return lines


def held_out_budgets(candidate):
    """A candidate's held-out rms in noise units from its evidence terms (charged residual over the
    variance each was judged with), as the report's held-out gap counts it; None without terms."""
    terms = ((candidate or {}).get("evidence") or {}).get("terms") or []
    if not terms:
        return None
    return math.sqrt(sum(t["charged"] ** 2 / t["variance"] for t in terms) / len(terms))


def closure_beyond_noise(summary):
    """The named effect's share of the held-out gap beyond noise: the report's
    verdict.gap_closure_beyond_noise, or (a summary from before that field) the same formula,
    1 - sqrt(max(b_effect^2 - 1, 0)) / sqrt(b_base^2 - 1), on the candidates' evidence terms."""
    v = summary.get("verdict") or {}
    if "gap_closure_beyond_noise" in v:
        return v["gap_closure_beyond_noise"]
    if not v.get("effect"):
        return None
    cands = summary.get("candidates") or []
    base = next((c for c in cands if c.get("effect") is None), None)
    mine = next((c for c in cands if c.get("effect") == v["effect"]), None)
    b_base, b_eff = held_out_budgets(base), held_out_budgets(mine)
    if b_base is None or b_eff is None or b_base <= 1:
        return None
    return 1 - math.sqrt(max(b_eff ** 2 - 1, 0)) / math.sqrt(b_base ** 2 - 1)


def write_matrix(rows, work, wall):
    failed = [r for r in rows if "twin_error" in r]
    rows = [r for r in rows if "twin_error" not in r]
    hidden = list(dict.fromkeys(r["hidden"] for r in rows))
    found = sorted(set(r["verdict"] for r in rows) | set(hidden), key=lambda e: (e != "none", e))
    lines = ["| hidden \\ verdict | " + " | ".join(found) + " |",
             "| --- | " + " | ".join("---" for _ in found) + " |"]
    for h in hidden:
        counts = [sum(1 for r in rows if r["hidden"] == h and r["verdict"] == f) for f in found]
        lines.append(f"| {h} | " + " | ".join(str(n) for n in counts) + " |")
    eff = [r for r in rows if r["hidden"] != "none"]
    null = [r for r in rows if r["hidden"] == "none"]
    hits = [r for r in eff if r["verdict"] == r["hidden"]]
    g = [r["gap_closure"] for r in hits if r["gap_closure"] is not None]
    g_noise = [r.get("gap_closure_beyond_noise") for r in hits]
    g_noise = [x for x in g_noise if x is not None]
    g_all = [r["candidates_g"].get(r["hidden"]) for r in eff]
    g_all = [x for x in g_all if x is not None]
    over = [r for r in eff if (r["base_gap"] or {}).get("exceeds_budget")]
    lines += ["",
              f"- twins whose base held-out gap exceeds the gap threshold (gap_budgets): {len(over)} of "
              f"{len(eff)}; identified among those: "
              f"{sum(1 for r in over if r['verdict'] == r['hidden'])}",
              f"- top-1 identification: {len(hits)} of {len(eff)}"
              + (f" ({100 * len(hits) / len(eff):.0f}%)" if eff else ""),
              f"- null false positives: {sum(1 for r in null if r['verdict'] != 'none')} of {len(null)}",
              f"- median held-out gap closure of the correct verdicts: "
              + (f"{statistics.median(g):.2f}" if g else "n/a (none)"),
              f"- median gap closure beyond noise of the correct verdicts: "
              + (f"{statistics.median(g_noise):.2f} over {len(g_noise)}" if g_noise else "n/a"),
              f"- median G of the hidden effect's own candidate (verdict or not): "
              + (f"{statistics.median(g_all):.2f}" if g_all else "n/a"),
              f"- time: {sum(r['twin_seconds'] + r['diagnosis_seconds'] for r in rows) / 3600:.2f} h "
              f"of twins and diagnoses over these {len(rows)} rows (this part's wall "
              f"{wall / 60:.1f} min); the first diagnosis "
              f"{rows[0]['diagnosis_seconds']:.0f} s (it runs the grids, unless the job store of "
              f"an earlier run in the same --out has them), the others median "
              f"{statistics.median(r['diagnosis_seconds'] for r in rows[1:] or rows):.0f} s"]
    null_gaps = [(r["base_gap"] or {}).get("held_out_budgets") for r in null]
    null_gaps = [x for x in null_gaps if x is not None]
    if null_gaps:
        t = null_threshold(null_gaps)
        lines += [f"- null twins' base held-out gap (rms in budgets), sorted: "
                  + ", ".join(f"{x:.2f}" for x in sorted(null_gaps)),
                  f"- gap threshold that at most 10% of these {len(null_gaps)} nulls exceed: "
                  f"{t:.2f} budgets; effect twins above it: "
                  f"{sum(1 for r in eff if ((r['base_gap'] or {}).get('held_out_budgets') or 0) > t)}"
                  f" of {len(eff)}"]
    def evidence(r):
        return ((r.get("evidence") or {}).get("value"))
    # An undetermined verdict judged nothing (the fit on a bound, no held-out residual): its
    # contenders' evidence is no sample of what a judged null gives.
    null_evidence = [evidence(r) for r in null
                     if evidence(r) is not None and not r.get("undetermined")]
    if null_evidence:
        t = null_threshold(null_evidence)
        used = (null[0].get("evidence") or {}).get("threshold")
        lines += [f"- null twins' best contender evidence (nats over the base), sorted: "
                  + ", ".join(f"{x:.2f}" for x in sorted(null_evidence)),
                  f"- evidence threshold that at most 10% of these {len(null_evidence)} judged nulls "
                  f"exceed: {t:.2f} nats (the requests used {used}); effect twins whose best "
                  f"contender exceeds it: {sum(1 for r in eff if (evidence(r) or -1e300) > t)} "
                  f"of {len(eff)}, the hidden effect among them: "
                  f"{sum(1 for r in eff if (evidence(r) or -1e300) > t and (r.get('evidence') or {}).get('effect') == r['hidden'])}"]
    lines += detection_limits(eff)
    if failed:
        lines += [f"- twins that could not be made (left out): "
                  + ", ".join(f"{r['hidden']}-{r['seed']}" for r in failed)]
    text = "\n".join(lines) + "\n"
    open(os.path.join(work, "matrix.md"), "w").write(text)
    print(text)
    print("results:", os.path.join(work, "results.json"))


if __name__ == "__main__":
    main()
