#!/usr/bin/env python3
"""The rock benchmark (docs/rock-benchmark.md): every rock of examples/rocks/rocks.csv calibrated by
its own request (examples/rocks/ROCK.json) on a `rockcal serve` of its own.

Each finished rock appends one JSON line to --out: the lab values, the verdict and its reason, the
predicted UCS and BTS (lab units, with their relative errors and 90% intervals), E and nu measured
at the estimate, the estimate and 90% intervals of F_r0 and F_s0 (model units), the runs, how many
of them were quasi-static by their own measure, and the wall time. Rocks already in --out are
skipped, so the benchmark may be run in parts; then the markdown table of every row in --out is
written between the table markers of --doc, with the command that produced it.

rocks.csv holds the numbers; a request restates them (targets, lab E, nu, density, specimen,
lab_uncertainty = sd / mean). Before anything runs, every request is checked against its row and
the first disagreement stops the script, naming the file, the field and both values; --check only
does that.

  bench/rock_benchmark.py [ROCK ...] [--build build] [--out bench/results/rocks.jsonl]
      [--doc docs/rock-benchmark.md] [--max-evaluations N] [--table-only] [--check]

ROCK: names of rocks.csv's `rock` column (default: all). --max-evaluations overrides the requests'
budget (a reduced run: give it its own --out and --doc). On demand only (up to about 30 minutes a
rock on 2 idle cores at the requests' budget); it builds nothing.
"""
import argparse
import csv
import json
import math
import os
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from rockcal_service import append_row, call, finish, load_rows, start_server  # noqa: E402

ROCKS = os.path.join(ROOT, "examples", "rocks")
BEGIN = "<!-- rock table: written by bench/rock_benchmark.py -->"
END = "<!-- end of rock table -->"


def lab_values(row):
    number = lambda key: float(row[key]) if row[key] else None
    return {"ucs_mpa": number("ucs_mpa"), "bts_mpa": number("bts_mpa"),
            "youngs_modulus_gpa": number("youngs_modulus_gpa"),
            "poisson_ratio": number("poisson_ratio"),
            "nu_from_source": row["nu_from_source"] == "yes"}


def close(a, b, rel=1e-3):
    return abs(a - b) <= rel * abs(b)


def lab_strength(target, test, specimen):
    """The lab strength (Pa) a request's UCT or BTT target states: "strength" itself, or a peak load
    read as UCS = 4P / (pi D^2) or BTS = 2P / (pi D t)."""
    if "strength" in target:
        return target["strength"]
    d = specimen["diameter"]
    if test == "uct":
        return 4 * target["peak_load"] / (math.pi * d * d)
    return 2 * target["peak_load"] / (math.pi * d * specimen["thickness"])


def disagreement(row, request):
    """The first field of a rock's request that differs from its rocks.csv row, as
    (field, request value, rocks.csv value), or None."""
    number = lambda key, scale=1.0: float(row[key]) * scale if row[key] else None
    lab = request["targets"]["lab"]
    specimen, material = lab["specimen"], lab["material"]
    inference = request.get("inference", {}).get("lab_uncertainty", {})
    pairs = [
        ("targets.uct", lab_strength(request["targets"]["uct"], "uct", specimen),
         number("ucs_mpa", 1e6)),
        ("targets.btt", lab_strength(request["targets"]["btt"], "btt", specimen),
         number("bts_mpa", 1e6)),
        ("targets.lab.material.youngs_modulus", material["youngs_modulus"],
         number("youngs_modulus_gpa", 1e9)),
        ("targets.lab.material.nu", material["nu"], number("poisson_ratio")),
        ("targets.youngs_modulus", request["targets"].get("youngs_modulus"),
         number("youngs_modulus_gpa", 1e9)),
        # A nu the source does not give stands in for the material only: it is no target.
        ("targets.poisson_ratio", request["targets"].get("poisson_ratio"),
         number("poisson_ratio") if row["nu_from_source"] == "yes" else None),
        ("job.material.nu", request["job"]["material"]["nu"], number("poisson_ratio")),
        ("targets.lab.material.density", material["density"], number("density_kg_m3")),
        ("targets.lab.specimen.diameter", specimen["diameter"], number("core_diameter_mm", 1e-3)),
        ("targets.lab.specimen.diameter", specimen["diameter"], number("disc_diameter_mm", 1e-3)),
        ("targets.lab.specimen.height", specimen["height"], number("core_height_mm", 1e-3)),
        ("targets.lab.specimen.thickness", specimen["thickness"],
         number("disc_thickness_mm", 1e-3))]
    for field, value, expected in pairs:
        if (value is None) != (expected is None) or (value is not None and not close(value, expected)):
            return field, value, expected
    for test, mean, sd in (("uct", "ucs_mpa", "ucs_sd_mpa"), ("btt", "bts_mpa", "bts_sd_mpa")):
        value, expected = inference.get(test), number(sd) / number(mean) if row[sd] else None
        if (value is None) != (expected is None) or (
                value is not None and abs(value - expected) > 0.005):
            return "inference.lab_uncertainty." + test, value, expected
    return None


def check_requests(rows):
    """Stops the script at the first request that disagrees with rocks.csv."""
    for rock, row in rows.items():
        path = os.path.join(ROCKS, rock + ".json")
        if not os.path.exists(path):
            sys.exit("rocks.csv names %s but %s does not exist" % (rock, path))
        wrong = disagreement(row, json.load(open(path)))
        if wrong:
            sys.exit("%s: %s is %s, rocks.csv says %s" % ((path,) + wrong))


def quasi_static_count(history):
    """(quasi-static, runs that reported the measure) over every run of the search."""
    slow = measured = 0
    for e in history:
        for test in ("uct", "btt"):
            for x in ((e.get("ensemble") or {}).get(test) or {}).get("realisations", []):
                if x.get("quasi_static") is not None:
                    measured += 1
                    slow += bool(x["quasi_static"])
    return slow, measured


def row_of(rock, lab, request, summary, wall_seconds):
    post = summary.get("posterior") or {}
    props = summary.get("rock_properties") or {}
    slow, measured = quasi_static_count(summary.get("history", []))
    row = {"rock": rock, "lab": lab, "max_evaluations": request["max_evaluations"],
           "verdict": summary.get("verdict"), "verdict_reason": summary.get("verdict_reason"),
           "runs": post.get("runs"), "quasi_static_runs": slow, "measured_runs": measured,
           "wall_seconds": round(wall_seconds, 1)}
    if post:
        row.update({
            "ucs_pa": props.get("ucs_pa"), "bts_pa": props.get("bts_pa"),
            "ucs_error": post["uct"]["relative_error"], "bts_error": post["btt"]["relative_error"],
            "youngs_modulus_pa": props.get("youngs_modulus_pa"),
            "poisson_ratio": props.get("poisson_ratio"),
            "estimate": post["estimate"], "fr0": post["fr0"], "fs0": post["fs0"],
            "unique": post["unique"], "acceptance": post.get("acceptance")})
    return row


def run_rock(url, rock, lab, max_evaluations):
    request = json.load(open(os.path.join(ROCKS, rock + ".json")))
    if max_evaluations:
        request["max_evaluations"] = max_evaluations
    t0 = time.time()
    status = finish(url, call(f"{url}/api/v1/campaigns", request)["id"])
    summary = status.get("summary") or {}
    if not summary:
        return {"rock": rock, "lab": lab, "max_evaluations": request["max_evaluations"],
                "verdict": None, "error": status.get("error") or "the campaign " + status["state"],
                "wall_seconds": round(time.time() - t0, 1)}
    return row_of(rock, lab, request, summary, time.time() - t0)


def pct(x):
    return "" if x is None else "%+.1f%%" % (100 * x)


def measured_cell(m, scale, fmt, lab, relative):
    """E or nu at the estimate (mean over its runs) and its difference from the lab's: relative
    for E, absolute for nu."""
    if not m or m.get("value") is None:
        return "not measured"
    v = m["value"] * scale
    if lab is None:
        return fmt % v
    diff = "%+.0f%%" % (100 * (v / lab - 1)) if relative else "%+.2f" % (v - lab)
    return "%s (%s)" % (fmt % v, diff)


def table(rows):
    head = ("| rock | lab UCS / BTS (MPa) | lab E (GPa) / nu | predicted UCS (MPa) | predicted BTS "
            "(MPa) | E at the estimate (GPa) | nu at the estimate | F_r0 estimate [90%] | F_s0 "
            "estimate [90%] | verdict | runs (quasi-static) | wall time |")
    lines = [head, "|" + " --- |" * 12]
    for r in rows:
        lab = r["lab"]
        nu_given = lab.get("nu_from_source", True)
        cells = [r["rock"], "%g / %g" % (lab["ucs_mpa"], lab["bts_mpa"]),
                 "%g / %g%s" % (lab["youngs_modulus_gpa"], lab["poisson_ratio"],
                                "" if nu_given else " (assumed, no target)")]
        if "estimate" in r:
            strength = lambda s, e: "%.4g (%s) [%.4g, %.4g]" % (
                s["value"] / 1e6, pct(e), s["interval"][0] / 1e6, s["interval"][1] / 1e6)
            interval = lambda est, iv: "%.3g [%.3g, %.3g]" % (est, iv[0], iv[1])
            cells += [strength(r["ucs_pa"], r["ucs_error"]), strength(r["bts_pa"], r["bts_error"]),
                      measured_cell(r["youngs_modulus_pa"], 1e-9, "%.3g", lab["youngs_modulus_gpa"], True),
                      measured_cell(r["poisson_ratio"], 1, "%.2f",
                                    lab["poisson_ratio"] if nu_given else None, False),
                      interval(r["estimate"]["fr0"], r["fr0"]), interval(r["estimate"]["fs0"], r["fs0"])]
        else:
            cells += ["no posterior"] + [""] * 5
        verdict = r.get("verdict") or "none"
        accepted = r.get("acceptance") or {}
        if verdict == "feasible" and accepted.get("source") == "lab_uncertainty":
            verdict += " within the lab's uncertainty (UCS %.0f%%, BTS %.0f%%)" % (
                100 * accepted["uct"], 100 * accepted["btt"])
        if r.get("max_evaluations"):
            verdict += " (budget %d)" % r["max_evaluations"]
        cells += [verdict, "%s (%s of %s)" % (r.get("runs"), r.get("quasi_static_runs"),
                                              r.get("measured_runs")),
                  "%.1f min" % (r["wall_seconds"] / 60)]
        lines.append("| " + " | ".join(str(c) for c in cells) + " |")
    return "\n".join(lines)


def write_doc(path, rows, command):
    text = open(path).read() if os.path.exists(path) else "# Rock benchmark\n\n%s\n%s\n" % (BEGIN, END)
    if BEGIN not in text or END not in text:
        sys.exit("%s has no table markers (%s ... %s)" % (path, BEGIN, END))
    body = ("Written by `%s` from %d row(s); the verdicts' reasons are in the results file.\n\n%s\n"
            % (command, len(rows), table(rows)) if rows else "No rock has been run yet.\n")
    head, rest = text.split(BEGIN, 1)
    open(path, "w").write(head + BEGIN + "\n" + body + END + rest.split(END, 1)[1])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("rocks", nargs="*")
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "rocks.jsonl"))
    ap.add_argument("--doc", default=os.path.join(ROOT, "docs", "rock-benchmark.md"))
    ap.add_argument("--max-evaluations", type=int)
    ap.add_argument("--table-only", action="store_true")
    ap.add_argument("--check", action="store_true")
    a = ap.parse_args()
    rows = {r["rock"]: r for r in csv.DictReader(open(os.path.join(ROCKS, "rocks.csv")))}
    check_requests(rows)
    if a.check:
        print("%d requests agree with rocks.csv" % len(rows))
        return
    labs = {rock: lab_values(row) for rock, row in rows.items()}
    unknown = [r for r in a.rocks if r not in labs]
    if unknown:
        sys.exit("unknown rock(s) %s; rocks.csv has %s" % (", ".join(unknown), ", ".join(labs)))
    done = load_rows(a.out, "rock")
    todo = [] if a.table_only else [r for r in (a.rocks or list(labs)) if r not in done]
    if todo:
        os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
        work = tempfile.mkdtemp(prefix="rockcal-rocks.")
        proc, url = start_server(a.build, work)
        try:
            for rock in todo:
                row = run_rock(url, rock, labs[rock], a.max_evaluations)
                done[rock] = row
                append_row(a.out, row)
        finally:
            proc.terminate()
            proc.wait()
    rows = [done[r] for r in labs if r in done]
    command = " ".join(["bench/rock_benchmark.py"] + sys.argv[1:])
    write_doc(a.doc, rows, command)
    print(table(rows))


if __name__ == "__main__":
    main()
