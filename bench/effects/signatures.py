#!/usr/bin/env python3
"""Each effect's signature: what it does to every observable once the bond strengths are re-fitted
to the same UCS and BTS (docs/effects.md, "Signatures"; issue 18 item 3).

An effect a diagnosis can name must leave a mark the calibration cannot absorb. Two observables
(UCS, BTS) fix the two strengths, so the mark is what is left on the others after the strengths
are moved to restore those two. For each effect at its "strong" value:

  1. run the base model (no effect) at --bond and at F_r0 and F_s0 each x --step, on --seeds seeds:
     the Jacobian J of ln(every observable) in (ln F_r0, ln F_s0);
  2. run the effect at --bond; solve J_cal d = -(change of ln UCS, ln BTS) for the strength step d;
  3. run the effect again at the re-fitted strengths exp(ln bond + d) (one Newton step; the UCS and
     BTS left after it are printed, "cal left");
  4. the signature of observable k is ln(effect at the re-fit / base), in ln and in standard
     errors of that difference: the seeds' scatter of both ensembles, and the step's own
     uncertainty (from the scatter of the UCS and BTS it restores) through the Jacobian.

Observables (all at D/R --size, seeded FCC lattice, the engine's default flattened disc):
  ucs, E (UCT modulus), eps_peak (UCT peak strain), tri_lo/tri_hi (triaxial sigma_1 at 0.1 and
  0.3 x the base UCS), ucs_hd1 (UCT at H/D = 1), rate (ln(UCS at 4x speed / UCS) / ln 4), bts,
  bts_size (ln(BTS at 1.5 D / BTS)), bts_jaws (BTS with ISRM curved jaws), bts_rate (ln(BTS at 4x
  speed / BTS) / ln 4).

  bench/effects/signatures.py [--build build] [--out runs/signatures] [--size 20] [--seeds 3]
      [--bond 64,128] [--step 1.2] [--jobs 2] [--effects heterogeneity:weibull_m=2,...]
      [--slow-factor 1]  (0.25: the two-rate loading of the diagnosis's twin design)

Runs are kept in OUT/NAME/, so a rerun only runs what is missing; delete OUT after rebuilding the
engine. Writes OUT/signatures.json and prints the markdown table.
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

# The registry's "strong" end of each effect's fitted parameter (docs/diagnosis.md, "Candidate
# effects"); packing's random packing needs its radius ratio in the sample instead.
STRONG = ("heterogeneity:weibull_m=2,packing:radius_ratio=2,platen_friction:mu=0.5,"
          "flaws:fraction=0.15,rate:speed_factor=8,compression_coupling:coupling=0,"
          "post_break_friction:mu=0.05,interaction_range:factor=1.5,"
          "rolling_resistance:mu_r=0.3,brazilian_flats:angle_deg=10")

OBSERVABLES = ["ucs", "E", "eps_peak", "tri_lo", "tri_hi", "ucs_hd1", "rate", "bts", "bts_size",
               "bts_jaws", "bts_rate"]
CALIBRATION = ["ucs", "bts"]




# The runs one model point needs: name -> (test, diameter factor, height / D, speed factor,
# confinement as a fraction of the base UCS, BTT geometry).
RUNS = {
    "uct": ("uct", 1.0, 2.0, 1.0, 0.0, None),
    "uct_hd1": ("uct", 1.0, 1.0, 1.0, 0.0, None),
    "uct_fast": ("uct", 1.0, 2.0, 4.0, 0.0, None),
    "tri_lo": ("triaxial", 1.0, 2.0, 1.0, 0.1, None),
    "tri_hi": ("triaxial", 1.0, 2.0, 1.0, 0.3, None),
    "btt": ("btt", 1.0, 0.0, 1.0, 0.0, None),
    "btt_15": ("btt", 1.5, 0.0, 1.0, 0.0, None),
    "btt_jaws": ("btt", 1.0, 0.0, 1.0, 0.0, "curved_jaws"),
    "btt_fast": ("btt", 1.0, 0.0, 4.0, 0.0, None),
}


def job(run, size, seed, bond, effects, base_ucs, slow_factor=1.0):
    test, dfac, hd, speed, conf, geometry = RUNS[run]
    d = size * dfac
    sample = {"diameter": d, "packing": "fcc", "radius": 1.0, "seed": seed}
    eff = copy.deepcopy(effects)
    if "packing" in eff:
        sample["packing"] = "random"
        sample["radius_ratio"] = eff.pop("packing")["radius_ratio"]
    if test == "btt":
        sample["thickness"] = d / 2
    else:
        sample["height"] = hd * d
    loading = {"platen_velocity": 0.05 * speed, "dt": "auto", "stop_load_fraction": 0.7,
               "max_strain": 0.2 if test != "btt" else 0.1}
    if slow_factor < 1.0:
        loading["slow_factor"] = slow_factor
    if conf:
        loading["confining_pressure"] = round(conf * base_ucs, 3)
    if geometry:
        loading["btt_geometry"] = geometry
    spec = {"test": test, "sample": sample,
            "material": {"density": 1.0, "kr": 8000, "nu": 0.2},
            "bond": {"fr0": bond[0], "fs0": bond[1]}, "contact": {"friction": 0.6},
            "loading": loading, "damping": {"local": 0.7}}
    if eff:
        spec["effects"] = eff
    return spec


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "runs", "signatures"))
    ap.add_argument("--size", type=float, default=20)
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--bond", default="64,128")
    ap.add_argument("--step", type=float, default=1.2)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--effects", default=STRONG)
    ap.add_argument("--slow-factor", type=float, default=1.0,
                    help="the two-rate loading's late speed as a fraction (the twin design's 0.25)")
    a = ap.parse_args()
    engine = os.path.join(a.build, "engine", "rockcal-dem")
    bond0 = [float(x) for x in a.bond.split(",")]
    seeds = list(range(1, a.seeds + 1))
    os.makedirs(a.out, exist_ok=True)
    pool = concurrent.futures.ThreadPoolExecutor(a.jobs)
    particles = {}

    def run_one(name, spec):
        return run_job(engine, os.path.join(a.out, name), spec)

    def point(label, bond, effects, base_ucs):
        """Every observable's per-seed ln values at one model point (None: no peak)."""
        names, futures = [], []
        for run in RUNS:
            for s in seeds:
                name = f"{label}_{run}_{s}"
                names.append((run, s))
                futures.append(pool.submit(run_one, name, job(run, a.size, s, bond, effects,
                                                              base_ucs, a.slow_factor)))
        res = {}
        for (run, s), fut in zip(names, futures):
            r = fut.result()
            res[(run, s)] = r if r.get("peak_reached") else None
            particles.setdefault(run, r.get("particles"))
        obs = {k: [] for k in OBSERVABLES}
        for s in seeds:
            u, f, h = res[("uct", s)], res[("uct_fast", s)], res[("uct_hd1", s)]
            b, b15, bj = res[("btt", s)], res[("btt_15", s)], res[("btt_jaws", s)]
            bf = res[("btt_fast", s)]
            t1, t2 = res[("tri_lo", s)], res[("tri_hi", s)]
            ln = lambda r, k="strength": math.log(r[k]) if r and r.get(k) else None
            obs["ucs"].append(ln(u))
            obs["E"].append(ln(u, "youngs_modulus"))
            obs["eps_peak"].append(math.log(u["peak_displacement"] / (2 * a.size))
                                   if u and u.get("peak_displacement") else None)
            obs["tri_lo"].append(ln(t1))
            obs["tri_hi"].append(ln(t2))
            obs["ucs_hd1"].append(ln(h))
            obs["rate"].append((ln(f) - ln(u)) / math.log(4) if u and f else None)
            obs["bts"].append(ln(b))
            obs["bts_size"].append(ln(b15) - ln(b) if b and b15 else None)
            obs["bts_jaws"].append(ln(bj))
            obs["bts_rate"].append((ln(bf) - ln(b)) / math.log(4) if b and bf else None)
        return obs

    def mean_se(values):
        v = [x for x in values if x is not None]
        if not v:
            return None, None, 0
        se = statistics.stdev(v) / math.sqrt(len(v)) if len(v) > 1 else float("nan")
        return statistics.mean(v), se, len(v)

    def means(obs):
        return {k: mean_se(v) for k, v in obs.items()}

    tag = lambda b: f"{b[0]:g}_{b[1]:g}"
    # The base UCS sets the confinements; the base UCT is the first run of the base point.
    base_uct = [run_one(f"base_{tag(bond0)}_uct_{s}", job("uct", a.size, s, bond0, {}, 0, a.slow_factor))
                for s in seeds]
    base_ucs = statistics.mean(r["strength"] for r in base_uct if r.get("peak_reached"))
    base = means(point(f"base_{tag(bond0)}", bond0, {}, base_ucs))
    # Jacobian columns: ln F_r0 and ln F_s0 each + ln step.
    h = math.log(a.step)
    jac = {}
    for col, b in (("fr0", [bond0[0] * a.step, bond0[1]]), ("fs0", [bond0[0], bond0[1] * a.step])):
        m = means(point(f"base_{tag(b)}", b, {}, base_ucs))
        jac[col] = {k: (m[k][0] - base[k][0]) / h if m[k][0] is not None and base[k][0] is not None
                    else None for k in OBSERVABLES}
    (a11, a12), (a21, a22) = [(jac["fr0"][k], jac["fs0"][k]) for k in CALIBRATION]
    det = a11 * a22 - a12 * a21

    table = {}
    for text in a.effects.split(","):
        name, eff = parse_effect(text)
        at0 = means(point(f"{name}_{tag(bond0)}", bond0, eff, base_ucs))
        if at0["ucs"][0] is None or at0["bts"][0] is None:
            table[name] = {"spec": text, "error": "no peak at the base strengths"}
            continue
        c1 = at0["ucs"][0] - base["ucs"][0]
        c2 = at0["bts"][0] - base["bts"][0]
        d1 = -(a22 * c1 - a12 * c2) / det
        d2 = -(-a21 * c1 + a11 * c2) / det
        refit = [round(bond0[0] * math.exp(d1), 3), round(bond0[1] * math.exp(d2), 3)]
        at1 = means(point(f"{name}_{tag(refit)}", refit, eff, base_ucs))
        # The step is only as sure as the UCS and BTS changes it restores (the seeds' scatter of
        # both ensembles; a 442-particle disc's BTS has se 0.23 in ln): its variance, carried to
        # each observable by the base Jacobian, is part of the signature's standard error. (The
        # Jacobian's own scatter and the ensembles' correlations are left out.)
        var_c = [at0[k][1] ** 2 + base[k][1] ** 2 for k in CALIBRATION]
        dd = [[-a22 / det, a12 / det], [a21 / det, -a11 / det]]  # d(d1, d2) / d(c1, c2)
        row = {"spec": text, "refit": refit, "before_refit": {}, "signature": {}}
        for k in OBSERVABLES:
            (m0, se0, n0), (m1, se1, n1), (mb, seb, nb) = at0[k], at1[k], base[k]
            if m0 is not None and mb is not None:
                row["before_refit"][k] = m0 - mb
            if m1 is None or mb is None:
                row["signature"][k] = None
                continue
            j = (jac["fr0"][k] or 0.0, jac["fs0"][k] or 0.0)
            var_step = sum((j[0] * dd[0][i] + j[1] * dd[1][i]) ** 2 * var_c[i] for i in range(2))
            se = math.sqrt(se1 ** 2 + seb ** 2 + var_step)
            row["signature"][k] = {"ln": m1 - mb, "se": se, "z": (m1 - mb) / se if se > 0 else None,
                                   "se_seeds": math.hypot(se1, seb), "n": [n1, nb]}
        table[name] = row
    pool.shutdown()

    summary = {"size": a.size, "seeds": a.seeds, "bond": bond0, "base_ucs": base_ucs,
               "particles": particles, "base": {k: base[k][:2] for k in OBSERVABLES},
               "jacobian": jac, "effects": table}
    with open(os.path.join(a.out, "signatures.json"), "w") as f:
        json.dump(summary, f, indent=1)

    print(f"D/R {a.size:g}, {a.seeds} seeds, base ({bond0[0]:g}, {bond0[1]:g}), UCS {base_ucs:.2f}; "
          f"particles: " + ", ".join(f"{k} {v}" for k, v in particles.items()))
    print("Signature: change of ln(observable) with the strengths re-fitted to the base UCS and BTS"
          " (rate, bts_rate: of the slopes d ln UCS, d ln BTS / d ln speed; bts_size: of ln(BTS 1.5D / BTS)); "
          "in brackets, in standard errors")
    print("| effect | re-fit (fr0, fs0) | " + " | ".join(OBSERVABLES) + " |")
    print("| --- | --- | " + " | ".join("---" for _ in OBSERVABLES) + " |")
    for name, row in table.items():
        if "error" in row:
            print(f"| {name} | {row['error']} |" + " |" * len(OBSERVABLES))
            continue
        cells = []
        for k in OBSERVABLES:
            s = row["signature"][k]
            cells.append("-" if s is None else
                         f"{s['ln']:+.3f} ({s['z']:+.1f})" if s["z"] is not None else
                         f"{s['ln']:+.3f}")
        print(f"| {name} | {row['refit'][0]:g}, {row['refit'][1]:g} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
