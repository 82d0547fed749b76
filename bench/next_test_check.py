#!/usr/bin/env python3
"""The next-test check on engine twins (docs/diagnosis.md, "The next test").

For a twin the calibration observations cannot name its hidden effect from, the diagnosis names a
lab test that would show it. The check: diagnose the twin ("before"), take the test the report
names for the hidden effect (`next_test.invisible` for that effect, else `next_test.leading` when
it separates that effect), make the same twin with that test measured too as a calibration
observation (`rockcal twin --next-test`), and diagnose it ("after"). The check passes when the
after verdict names the hidden effect. A test named without showing the effect (`visible` false:
the report says no menu test shows it) is run all the same, to check that forecast.

--drop ID first removes observation ID from the twin (a dataset without a test the design has),
so the check can be made on an effect the full design identifies: "before" is the twin less ID;
when the test named is the dropped one, "after" is the twin itself (that test measured again);
another test named fails the check (no twin holds the dataset with it).

  bench/next_test_check.py --twin DIR/twin_NAME.json [--drop ID] [--request R.json]
                           [--build build] [--server URL | --store DIR] [--results F.jsonl]

The twin is one `bench/diagnosis_confusion.py` made (its truth beside it, NAME.truth.json); run on
the same --out directory's store (--server: that script's running server; else a server of its own
on --store DIR, that directory) the design runs come from the store. One JSON line per check is appended
to --results. On demand only: tens of minutes a check on 2 cores.
"""
import argparse
import json
import os
import subprocess
import sys
import time

from diagnosis_confusion import ROOT, get, start_server


def diagnose(rockcal, url, request, dataset_file, name, work):
    req = dict(request)
    req["name"] = name
    req["dataset_file"] = os.path.basename(dataset_file)
    tag = os.path.basename(dataset_file)[:-len(".json")]
    req_file = os.path.join(work, f"request_{tag}.json")
    json.dump(req, open(req_file, "w"), indent=1)
    t0 = time.time()
    out = subprocess.run([rockcal, "diagnose", req_file, "--server", url, "--html",
                          os.path.join(work, f"report_{tag}.html")],
                         check=True, capture_output=True, text=True).stdout
    cid = int(out.split("diagnosis campaign ", 1)[1].split()[0])
    s = get(f"{url}/api/v1/campaigns/{cid}")["summary"]
    v = s.get("verdict", {})
    return {"campaign": cid, "verdict": v.get("effect") or "none", "label": v.get("label"),
            "parameter": (v.get("parameter") or {}).get("value"),
            "gap_closure": v.get("gap_closure"), "evidence": (v.get("evidence") or {}).get("value"),
            "confidence": (v.get("confidence") or {}).get("level"),
            "held_out_budgets": (s.get("gap") or {}).get("held_out_budgets"),
            "reason": v.get("reason"), "seconds": round(time.time() - t0, 1)}, s


def test_for(summary, effect):
    """The test the report names for `effect`: the test, its discrimination, whether it shows the
    effect beyond budget + lab uncertainty (else it is only the best of tests that do not), and
    where it was found."""
    nt = summary.get("next_test") or {}
    for x in nt.get("invisible") or []:
        if x.get("effect") == effect and x.get("test"):
            return x["test"], x.get("discrimination"), x.get("visible"), "invisible"
    lead = nt.get("leading") or {}
    if effect in (lead.get("separates") or []) and lead.get("test"):
        return lead["test"], lead.get("discrimination"), lead.get("visible"), "leading"
    return None, None, None, None


def as_test(observation):
    """A twin's measured menu test (model units) in the report's shape, for `--next-test`."""
    c = dict(observation.get("conditions", {}))
    if "loading_rate" in c:
        c["platen_velocity"] = c.pop("loading_rate")
    c["units"] = "model"
    return {"id": observation["id"], "test": observation["test"],
            "observable": observation["observable"], "conditions": c}


def same_test(test, observation):
    """Whether a report's test (model units) is the dataset observation's test and conditions."""
    if test["test"] != observation["test"] or test["observable"] != observation["observable"]:
        return False
    tc, oc = test["conditions"], observation.get("conditions", {})
    pairs = [("diameter", "diameter"), ("height", "height"), ("thickness", "thickness"),
             ("confining_pressure", "confining_pressure"), ("platen_velocity", "loading_rate")]
    return all(abs(tc.get(t, 0.0) - oc.get(o, 0.0)) <= 1e-9 * max(1.0, abs(tc.get(t, 0.0)))
               for t, o in pairs)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--twin", required=True)
    ap.add_argument("--drop", default=None)
    ap.add_argument("--request", default=os.path.join(ROOT, "bench", "diagnose_twin_d20_local.json"))
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--server", default=None)
    ap.add_argument("--store", default=None,
                    help="directory of the job store for a server of its own (default the twin's)")
    ap.add_argument("--results", default=None)
    a = ap.parse_args()
    work = os.path.dirname(os.path.abspath(a.twin))
    rockcal = os.path.join(a.build, "api", "rockcal")
    request = json.load(open(a.request))
    request.pop("dataset_file", None)
    truth_file = a.twin[:-len(".json")] + ".truth.json"
    truth = json.load(open(truth_file))
    effect = truth["effect"]
    name = os.path.basename(a.twin)[len("twin_"):-len(".json")]
    before_file = a.twin
    if a.drop:
        d = json.load(open(a.twin))
        kept = [o for o in d["observations"] if o["id"] != a.drop]
        if len(kept) == len(d["observations"]):
            sys.exit(f"next_test_check: {a.twin} has no observation {a.drop}")
        d["observations"] = kept
        before_file = os.path.join(work, f"twin_{name}-less-{a.drop}.json")
        json.dump(d, open(before_file, "w"), indent=1)

    proc = None
    url = a.server
    if not url:
        proc, url = start_server(a.build, a.store or work)
    try:
        before, summary = diagnose(rockcal, url, request, before_file,
                                   f"next-test check, before: {name}" +
                                   (f" less {a.drop}" if a.drop else ""), work)
        test, discrimination, visible, found = test_for(summary, effect)
        row = {"twin": name, "hidden": effect, "value": truth.get("value"), "seed": truth["seed"],
               "dropped": a.drop, "before": before, "test": test,
               "discrimination": discrimination, "visible": visible, "found_in": found,
               "request": os.path.basename(a.request)}
        print(f"{name}: before {before['verdict']} ({before['label']}); next test "
              f"{test and test['id']} ({discrimination})", flush=True)
        dropped = None
        if a.drop:
            dropped = next(o for o in json.load(open(a.twin))["observations"] if o["id"] == a.drop)
            row["named_the_dropped_test"] = bool(test) and same_test(test, dropped)
        if test and dropped is not None and not row["named_the_dropped_test"]:
            row["passed"] = False  # another test named: no twin holds the dataset with it
        elif test:
            if dropped is not None:
                after_file = a.twin  # the dropped test measured again: the twin itself
            else:
                after_file = os.path.join(work, f"twin_{name}-with-{test['id']}.json")
                test_file = after_file[:-len(".json")] + ".test.json"
                # Tests the twin measured already (a check on a check's twin) stay, first.
                earlier = [as_test(o) for o in json.load(open(a.twin))["observations"]
                           if o["id"].startswith("menu-")]
                json.dump(earlier + [test], open(test_file, "w"), indent=1)
                cmd = [rockcal, "twin", "--effect", effect, "--seed", str(truth["seed"]),
                       "--job", os.path.join(work, "template.json"), "--out", after_file,
                       "--engine", os.path.join(a.build, "engine", "rockcal-dem"),
                       "--resolution", str(truth.get("resolution", 1)), "--next-test", test_file]
                if truth.get("value") is not None:
                    cmd += ["--value", str(truth["value"])]
                if truth.get("truth_seed") is not None:
                    cmd += ["--truth-seed", str(truth["truth_seed"])]
                subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
            row["after"], _ = diagnose(rockcal, url, request, after_file,
                                       f"next-test check, after: {name} with {test['id']}", work)
            row["passed"] = row["after"]["verdict"] == effect
            print(f"{name}: after {row['after']['verdict']} ({row['after']['label']}), "
                  f"G {row['after']['gap_closure']}", flush=True)
        else:
            row["passed"] = False
        if a.results:
            with open(a.results, "a") as f:
                f.write(json.dumps(row) + "\n")
    finally:
        if proc:
            proc.terminate()
            proc.wait(timeout=60)


if __name__ == "__main__":
    main()
