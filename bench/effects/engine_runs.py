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


def add_run_options(parser, root, out_name, size, auto_transits, slow_factor):
    """--build, --out (runs/OUT_NAME), --log and --jobs: where the engine is, where runs are kept,
    the file that gets one JSON line per finished run, and how many run at once; --size (D/R),
    --seeds, and the loading: --auto-transits, --slow-factor, --past-window."""
    parser.add_argument("--build", default=os.path.join(root, "build"))
    parser.add_argument("--out", default=os.path.join(root, "runs", out_name))
    parser.add_argument("--log")
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--size", type=float, default=size)
    parser.add_argument("--seeds", type=int, default=1)
    parser.add_argument("--auto-transits", type=float, default=auto_transits)
    parser.add_argument("--slow-factor", type=float, default=slow_factor)
    # The tables in docs/loading-rate.md and docs/reach.md were measured with the late peaks
    # reported (the engine's default now ends such a run at the window without a peak).
    parser.add_argument("--past-window", choices=["stop", "speed_up"], default="speed_up")


def run_all(options, runs, line_of):
    """Runs [(key, name, spec)] with options.jobs at once (cached in OUT/NAME); appends
    line_of(name, result) to options.log as each finishes. Returns {key: result}."""
    import concurrent.futures
    engine = os.path.join(options.build, "engine", "rockcal-dem")
    results = {}
    with concurrent.futures.ThreadPoolExecutor(options.jobs) as pool:
        futures = {pool.submit(run_job, engine, os.path.join(options.out, name), spec): (key, name)
                   for key, name, spec in runs}
        for future in concurrent.futures.as_completed(futures):
            key, name = futures[future]
            results[key] = future.result()
            if options.log:
                with open(options.log, "a") as log:
                    log.write(json.dumps(line_of(name, results[key])) + "\n")
    return results
