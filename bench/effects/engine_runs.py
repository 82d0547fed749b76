"""What the effect studies share: effect specs on the command line and cached engine runs."""
import json
import os
import subprocess


def parse_effect(text):
    """"NAME:PARAM=X;PARAM=Y" (or "none") -> (NAME, the job's "effects" block)."""
    if text == "none":
        return "none", {}
    name, _, params = text.partition(":")
    values = {}
    for kv in filter(None, params.split(";")):
        key, _, value = kv.partition("=")
        values[key] = float(value)
    return name, {name: values}


def run_job(engine, out, spec):
    """Runs spec in directory out unless its result is there; {} when the engine refused it."""
    result = os.path.join(out, "result.json")
    if not os.path.exists(result):
        os.makedirs(out, exist_ok=True)
        with open(os.path.join(out, "job.json"), "w") as f:
            json.dump(spec, f)
        subprocess.run([engine, "run", os.path.join(out, "job.json"), "--out", out],
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
    if not os.path.exists(result):  # refused by the engine (its log says why)
        return {}
    with open(result) as f:
        return json.load(f)
