#!/usr/bin/python3
"""ESys-Particle version of rockcal's FCC UCT sample, for throughput comparisons only.

ESys-Particle is NOT a dependency of rockcal; this script is run on demand by bench/compare_esys.sh
(or by hand) when the Debian package `esys-particle` happens to be installed:

    mpirun -np 2 esysparticle bench/esys_uct.py --steps 500 --dt 0.0038863621594707708
    mpirun -np 3 esysparticle bench/esys_uct.py --steps 500 --workers 2 --result DIR/result.json

(rank 0 is ESys's master, which drives this script; the other ranks are workers). Under Open MPI as
root add --allow-run-as-root. The module is found by /usr/bin/python3, not by a pyenv python.

The sample is built from the same job JSON rockcal-dem reads (default examples/uct_paper.json):
  * the same FCC lattice as engine/packing/fcc.cpp (cube edge 2*sqrt(2)*R, cube axes along x, y, z,
    loading along z = [001]), the same cylinder cut (centres within D/2 - R/2 radially and
    H/2 - R/2 axially) and the same particle ids;
  * rotational bonds (RotBondPrms, scaling=False: raw N/m, N*m/rad and N) between particles whose
    centres are within (R_i + R_j)(1 + 1e-6), as rockcal does;
  * eq. 3 stiffnesses from K_r, nu and R, as engine/units.cpp. ESys applies its bending torque as
    K_b * theta / 2 (Model/ARotBondedInteraction.cpp), rockcal as K_b * theta, so ESys is given
    bendingK = 2 K_b to get the same bending stiffness;
  * strengths: normal F_r0, shear F_s0, twisting moment R F_s0 / 2, bending moment R F_r0 / 4 (the
    values rockcal's make_bond derives). ESys's failure criterion is not rockcal's (see
    docs/performance.md), which does not matter for throughput before bonds break;
  * unbonded contacts: RotFrictionPrms with K_n = K_r, K_s = K_s, mu = contact.friction, excluded
    for bonded pairs (rockcal: same linear law, same coefficients);
  * two frictionless elastic platens (NRotElasticWallPrms, K_n = K_r) touching the end particles,
    each moved towards the centre at loading.platen_velocity with rockcal's linear ramp over
    loading.ramp_fraction of the time to loading.max_strain;
  * local (Cundall) damping on forces and torques (LocalDampingPrms + RotLocalDampingPrms);
  * sphere mass rho 4/3 pi R^3 (ESys: I = 0.4 m R^2, as rockcal);
  * the time step: --dt, or "dt" from a rockcal result.json (--result), or the job's loading.dt.

It runs a fixed number of steps (a Python loop: move both platens, runTimeStep) and prints
particles, bonds, steps, wall seconds of the stepping loop and particle-steps per second, then one
line `ESYS_RESULT {json}` for scripts. Set-up and the first step (where ESys builds its neighbour
tables and interaction lists) are left out of the rate, as rockcal-dem leaves its set-up out of
wall_seconds; both are printed.
"""

import argparse
import json
import math
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_JOB = os.path.join(os.path.dirname(HERE), "examples", "uct_paper.json")


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--job", default=DEFAULT_JOB, help="rockcal job JSON (uct, fcc); default %(default)s")
    ap.add_argument("--steps", type=int, default=500, help="time steps to run, >= 2 (default %(default)s)")
    ap.add_argument("--dt", type=float, default=None, help="time step (s)")
    ap.add_argument("--result", default=None, help="rockcal result.json to take dt from")
    ap.add_argument("--workers", type=int, default=1, help="ESys worker processes; mpirun -np must be workers + 1")
    ap.add_argument("--verlet", type=float, default=0.3,
                    help="ESys verletDist in radii (rockcal's neighbour skin is 0.3 R); default %(default)s")
    ap.add_argument("--check-mass", action="store_true", help="print the model's particle masses (testing)")
    ap.add_argument("--diameter", type=float, default=None, help="override sample.diameter (testing)")
    ap.add_argument("--height", type=float, default=None, help="override sample.height (testing)")
    return ap.parse_args()


def job_parameters(args):
    with open(args.job) as f:
        job = json.load(f)
    if job.get("test", "uct") != "uct":
        raise SystemExit("esys_uct.py: only UCT jobs are supported")
    sample, material = job.get("sample", {}), job.get("material", {})
    if sample.get("packing", "fcc") != "fcc":
        raise SystemExit("esys_uct.py: only the FCC packing is supported")
    if "kr" not in material:
        raise SystemExit("esys_uct.py: the job must give material.kr (N/m)")
    bond, contact = job.get("bond", {}), job.get("contact", {})
    loading, damping = job.get("loading", {}), job.get("damping", {})
    if loading.get("platen_friction", 0.0) != 0.0:
        raise SystemExit("esys_uct.py: frictional platens are not modelled")
    if damping.get("viscous", 0.0) != 0.0:
        raise SystemExit("esys_uct.py: viscous damping is not modelled")
    p = {
        "D": float(args.diameter or sample.get("diameter", 10.0)),
        "H": float(args.height or sample.get("height", 28.0)),
        "R": float(sample.get("radius", 1.0)),
        "rho": float(material.get("density", 1.0)),
        "kr": float(material["kr"]),
        "nu": float(material.get("nu", 0.2)),
        "fr0": float(bond.get("fr0", 64.0)),
        "fs0": float(bond.get("fs0", 64.0)),
        "mu": float(contact.get("friction", 0.6)),
        "v": float(loading.get("platen_velocity", 0.05)),
        "ramp_fraction": float(loading.get("ramp_fraction", 0.01)),
        "max_strain": float(loading.get("max_strain", 0.05)),
        "alpha": float(damping.get("local", 0.7)),
    }
    dt = args.dt
    if dt is None and args.result:
        with open(args.result) as f:
            dt = float(json.load(f)["dt"])
    if dt is None and isinstance(loading.get("dt"), (int, float)):
        dt = float(loading["dt"])
    if dt is None:
        raise SystemExit("esys_uct.py: give --dt or --result (rockcal's result.json), or a numeric loading.dt")
    p["dt"] = dt
    return p


def eq3_stiffness(kr, nu, r):
    """Eq. 3 ratios, exactly as engine/units.cpp stiffness_from_kr."""
    ks = (1.0 - 3.0 * nu) / (1.0 + nu) * kr
    kb = (1.0 - 2.0 * nu) * r * r / (24.0 * (1.0 - nu)) * kr
    kt = (1.0 - 3.0 * nu) / (1.0 + nu) * kb
    return ks, kb, kt


def fcc_cylinder(D, H, R):
    """Same lattice walk and cut as engine/packing/fcc.cpp (same order, hence the same ids)."""
    a = 2.0 * math.sqrt(2.0) * R
    basis = ((0.0, 0.0, 0.0), (0.5 * a, 0.5 * a, 0.0), (0.5 * a, 0.0, 0.5 * a), (0.0, 0.5 * a, 0.5 * a))
    rmax = 0.5 * D - 0.5 * R + 1e-9
    zmax = 0.5 * H - 0.5 * R + 1e-9
    nx = int(0.5 * D / a) + 1
    nz = int(0.5 * H / a) + 1
    out = []
    for k in range(-nz, nz + 1):
        for j in range(-nx, nx + 1):
            for i in range(-nx, nx + 1):
                for b in basis:
                    x, y, z = i * a + b[0], j * a + b[1], k * a + b[2]
                    if x * x + y * y <= rmax * rmax and abs(z) <= zmax:
                        out.append((x, y, z))
    return out


def touching_pairs(centres, R, tolerance=1e-6):
    """Pairs (i < j) with |x_j - x_i| <= 2R (1 + tolerance), through a cell grid."""
    cell = 2.0 * R * (1.0 + tolerance) * 1.01
    grid = {}
    for n, (x, y, z) in enumerate(centres):
        grid.setdefault((math.floor(x / cell), math.floor(y / cell), math.floor(z / cell)), []).append(n)
    reach2 = (2.0 * R * (1.0 + tolerance)) ** 2
    pairs = []
    for (cx, cy, cz), members in grid.items():
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    other = grid.get((cx + dx, cy + dy, cz + dz))
                    if not other:
                        continue
                    for i in members:
                        xi, yi, zi = centres[i]
                        for j in other:
                            if j <= i:
                                continue
                            xj, yj, zj = centres[j]
                            if (xj - xi) ** 2 + (yj - yi) ** 2 + (zj - zi) ** 2 <= reach2:
                                pairs.append((i, j))
    return pairs


def log(msg):
    sys.stderr.write("esys_uct: %s\n" % msg)
    sys.stderr.flush()


def main():
    args = parse_args()
    p = job_parameters(args)
    if args.steps < 2:
        raise SystemExit("esys_uct.py: --steps must be at least 2")

    from esys.lsm import (LsmMpi, RotBondPrms, RotFrictionPrms, NRotElasticWallPrms,
                          LocalDampingPrms, RotLocalDampingPrms)
    from esys.lsm.geometry import SimpleSphere, TaggedIdConnection
    from esys.lsm.util import Vec3, BoundingBox

    t_setup = time.time()
    R = p["R"]
    ks, kb, kt = eq3_stiffness(p["kr"], p["nu"], R)
    centres = fcc_cylinder(p["D"], p["H"], R)
    pairs = touching_pairs(centres, R)
    mass = p["rho"] * 4.0 / 3.0 * math.pi * R ** 3

    log("%d particles, %d bonds; creating the model" % (len(centres), len(pairs)))
    workers = args.workers
    sim = LsmMpi(numWorkerProcesses=workers, mpiDimList=[1, 1, workers])  # slabs along the loading axis
    sim.initNeighbourSearch(particleType="RotSphere", gridSpacing=2.5 * R, verletDist=args.verlet * R)
    sim.setTimeStepSize(p["dt"])
    lo = [min(c[a] for c in centres) for a in range(3)]
    hi = [max(c[a] for c in centres) for a in range(3)]
    margin = 4.0 * R
    sim.setSpatialDomain(BoundingBox(Vec3(lo[0] - margin, lo[1] - margin, lo[2] - margin),
                                     Vec3(hi[0] + margin, hi[1] + margin, hi[2] + margin)))
    # In bulk: one createParticle per sphere is a master-worker round trip each (minutes for 43k).
    sim.createParticles([SimpleSphere(centre=Vec3(*c), radius=R, id=n, tag=0, mass=mass)
                         for n, c in enumerate(centres)])
    log("particles created")
    sim.createConnections([TaggedIdConnection(i, j, 0) for i, j in pairs])
    sim.createInteractionGroup(RotBondPrms(
        name="bonds", normalK=p["kr"], shearK=ks, torsionK=kt, bendingK=2.0 * kb,
        normalBrkForce=p["fr0"], shearBrkForce=p["fs0"],
        torsionBrkForce=R * p["fs0"] / 2.0, bendingBrkForce=R * p["fr0"] / 4.0,
        tag=0, scaling=False))
    sim.createInteractionGroup(RotFrictionPrms(
        name="friction", normalK=p["kr"], dynamicMu=p["mu"], staticMu=p["mu"], shearK=ks, scaling=False))
    sim.createExclusion("bonds", "friction")

    z_lo, z_hi = lo[2] - R, hi[2] + R
    sim.createWall(name="bottom", posn=Vec3(0.0, 0.0, z_lo), normal=Vec3(0.0, 0.0, 1.0))
    sim.createWall(name="top", posn=Vec3(0.0, 0.0, z_hi), normal=Vec3(0.0, 0.0, -1.0))
    sim.createInteractionGroup(NRotElasticWallPrms(name="bottom_wall", wallName="bottom", normalK=p["kr"]))
    sim.createInteractionGroup(NRotElasticWallPrms(name="top_wall", wallName="top", normalK=p["kr"]))
    sim.createInteractionGroup(LocalDampingPrms(name="damping", viscosity=p["alpha"]))
    sim.createInteractionGroup(RotLocalDampingPrms(name="rot_damping", viscosity=p["alpha"]))

    length = p["H"]
    t_max = p["max_strain"] * length / (2.0 * p["v"])
    t_ramp = p["ramp_fraction"] * t_max
    dt, v = p["dt"], p["v"]

    log("interactions created")

    def move_platens(step):
        """Both platens towards the centre, with rockcal's linear speed ramp."""
        t = step * dt
        ramp = min(1.0, (t + 0.5 * dt) / t_ramp) if t_ramp > 0 else 1.0
        d = v * ramp * dt
        sim.moveWallBy("bottom", Vec3(0.0, 0.0, d))
        sim.moveWallBy("top", Vec3(0.0, 0.0, -d))

    setup_s = time.time() - t_setup
    log("set-up took %.1f s; running %d steps" % (setup_s, args.steps))
    # A Python loop of runTimeStep, not sim.run(): in ESys-Particle 2.3.5 run() ends the
    # simulation (the workers leave), after which getWallForce() or exit() wait forever.
    # The first step is timed apart: ESys builds its neighbour tables and interaction lists there,
    # which rockcal-dem does during set-up (outside its wall_seconds).
    t0 = time.time()
    move_platens(0)
    sim.runTimeStep()
    first_s = time.time() - t0
    t0 = time.time()
    for step in range(1, args.steps):
        move_platens(step)
        sim.runTimeStep()
    wall = time.time() - t0
    timed = args.steps - 1

    f_top = sim.getWallForce("top")
    f_bottom = sim.getWallForce("bottom")
    load = 0.5 * (abs(f_top[2]) + abs(f_bottom[2]))
    n = sim.getNumParticles()
    if args.check_mass:
        masses = sorted(set(round(q.getMass(), 9) for q in sim.getParticleList()))
        log("particle masses in the model: %s (expected %.9g)" % (masses[:5], mass))
    out = {
        "engine": "esys-particle " + sim.getLsmVersion(),
        "workers": workers,
        "particles": n,
        "bonds": len(pairs),
        "steps": args.steps,
        "timed_steps": timed,
        "dt": dt,
        "setup_seconds": setup_s,
        "first_step_seconds": first_s,
        "wall_seconds": wall,
        "particle_steps_per_second": n * timed / wall if wall > 0 else float("nan"),
        "platen_load": load,
        "stiffness": {"kr": p["kr"], "ks": ks, "kt": kt, "kb": kb, "esys_bendingK": 2.0 * kb},
    }
    print("esys_uct: %d particles, %d bonds, %d steps of dt %.6g; steps 2-%d took %.2f s "
          "(set-up %.1f s, first step %.2f s): %.4g particle-steps/s with %d worker(s); "
          "platen load %.6g N"
          % (n, len(pairs), args.steps, dt, args.steps, wall, setup_s, first_s,
             out["particle_steps_per_second"], workers, load))
    print("ESYS_RESULT " + json.dumps(out))
    sys.stdout.flush()
    sim.exit()


if __name__ == "__main__":
    main()
