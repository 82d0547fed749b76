"""A `rockcal serve` of its own for a bench script: start it, talk to its REST API, wait for a
campaign; and the resumable results file (one JSON row a line). Shared by bench/bayes_twins.py and
bench/rock_benchmark.py."""
import json
import os
import subprocess
import sys
import time
import urllib.request


def call(url, body=None):
    data = None if body is None else json.dumps(body).encode()
    req = urllib.request.Request(url, data=data, headers={"Content-Type": "application/json"})
    with urllib.request.urlopen(req, timeout=120) as r:
        return json.load(r)


def start_server(build, work, workers=2):
    """`rockcal serve` on a fresh SQLite file in `work`, on a free loopback port; returns the
    process and its URL."""
    port_file = os.path.join(work, "port")
    log = open(os.path.join(work, "serve.log"), "w")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    proc = subprocess.Popen(
        [os.path.join(build, "api", "rockcal"), "serve", "--db", os.path.join(work, "bench.db"),
         "--listen", "127.0.0.1:0", "--port-file", port_file, "--workers", str(workers),
         "--ranks-per-job", "0"], stdout=log, stderr=subprocess.STDOUT, env=env)
    for _ in range(300):
        if os.path.exists(port_file) and open(port_file).read().strip():
            return proc, "http://127.0.0.1:" + open(port_file).read().strip()
        time.sleep(0.1)
    proc.kill()
    sys.exit("the server did not start (see %s)" % os.path.join(work, "serve.log"))


def finish(url, cid):
    """Polls campaign `cid` until it has ended; returns its status document."""
    while True:
        c = call(f"{url}/api/v1/campaigns/{cid}")
        if c["state"] in ("succeeded", "failed", "cancelled"):
            return c
        time.sleep(2)


def load_rows(path, key):
    """The rows already in a results file (one JSON object a line), by row[key]: what a resumable
    bench run skips."""
    done = {}
    if os.path.exists(path):
        for line in open(path):
            if line.strip():
                row = json.loads(line)
                done[row[key]] = row
    return done


def append_row(path, row):
    """Appends one finished row to the results file and prints it."""
    with open(path, "a") as f:
        f.write(json.dumps(row) + "\n")
    print(json.dumps(row), flush=True)
