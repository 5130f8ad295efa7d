"""``bouncer sweep``: an escape-rate map over a grid of eps, hole centre and/or hole width.

Every grid point is an escape scene of its own, made from a base escape scene (default
``paper-escape``: its start box, seed and chunk size) with one hole of the point's centre and
width at the point's eps, and the horizon ``horizon.collisions = n_star`` (no time horizon).
All points use the same seed, so they start from the same particles (common random numbers:
neighbouring cells differ by the model, not by the sample). Axes not swept take the base
scene's eps, first hole centre and first hole width.

Escape rate. A particle survives to n* when none of its first n* collisions lands in the hole,
i.e. it is censored at the horizon; with S survivors of N starts, P(n*) = S/N exactly, and

    rate = -ln(P(n*)) / n*                 (per collision)

the escape rate of P(n) ~ exp(-rate*n) averaged over the first n* collisions. It needs no fit
window, is defined wherever a particle survives, and costs at most n* collisions a particle.
Its 95% band maps the Wilson band of P(n*): [-ln(p_hi)/n*, -ln(p_lo)/n*] (inf when p_lo = 0).
S = 0 gives rate inf (the cell is saturated: lower n* or add particles).
Where a point is not a valid scene (the hole overlaps the start box, starts that do not
depart) it is skipped with the reason in ``note`` and left blank in the map.

Outputs in the sweep directory: ``sweep.csv`` (one row per grid point), ``escape-rate.png``
(heat map), ``sample.csv`` (the verification sample, with the point index) and
``manifest.json``. The chunks of all points go to one executor, here or on a Dask cluster
(``scheduler``), exactly as in ``reports.runs.driver``: flagged collisions are settled by verify
and a sample is verified in every chunk; one overstep fails the sweep.
"""

from __future__ import annotations

import math
import time
from contextlib import closing
from dataclasses import replace
from pathlib import Path

import numpy as np

from reports.runs import cluster, rundir
from reports.runs.chunk import check_result
from reports.runs.executor import Executor
from reports.runs.lock import RunLock
from reports.runs.manifest import ERROR_UNIT
from reports.runs.plan import make_plan
from reports.runs.provenance import git, now, versions
from reports.runs.rundir import RunFailed
from reports.runs.scenes import Scene, parse_scene
from reports.runs.survival import wilson

AXES = ("centre", "width", "eps")  # map axes in this order: the first swept is x, the next y
DEFAULT_GRID = {"centre": (0.0, 2.5, 6), "eps": (0.3, 0.9, 4)}
N_STAR = 50
PARTICLES = 2000
VERIFY_SAMPLES = 500
MAX_POINTS_PER_AXIS = 1000
COLUMNS = ("eps", "centre", "width", "particles", "n_star", "survivors", "p", "p_lo", "p_hi",
           "rate", "rate_lo", "rate_hi", "collisions", "note")
LABELS = {"eps": "eps", "centre": "hole centre phi_c", "width": "hole width"}


def grid_values(lo, hi, n, name):
    """``n`` evenly spaced values from lo to hi (n = 1: lo). ValueError if not sensible."""
    if n != int(n) or not 1 <= n <= MAX_POINTS_PER_AXIS:
        raise ValueError(f"--{name}: the number of points must be in 1..{MAX_POINTS_PER_AXIS},"
                         f" got {n}")
    n, lo, hi = int(n), float(lo), float(hi)
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise ValueError(f"--{name}: the range must be finite, got {lo!r} {hi!r}")
    if n > 1 and not lo < hi:
        raise ValueError(f"--{name}: need LO < HI for N > 1, got {lo!r} {hi!r}")
    return [float(f"{x:.12g}") for x in np.linspace(lo, hi, n)]  # 0.7, not 0.7000000000000001


def point_text(base, eps, centre, width, n_star, particles, verify_samples):
    """TOML of the escape scene at one grid point (validated by ``parse_scene``)."""
    name = f"{base.name}-sweep"
    return "\n".join([
        f"name = {name!r}",
        'kind = "escape"',
        f"description = 'sweep point of {base.name}: eps, centre, width ="
        f" {eps!r}, {centre!r}, {width!r}'",
        f"eps = {eps!r}",
        f"particles = {particles}",
        f"seed = {base.seed}",
        f"chunk_size = {base.chunk_size}",
        "[start]",
        f"phi = [{base.start_phi[0]!r}, {base.start_phi[1]!r}]",
        f"v = [{base.start_v[0]!r}, {base.start_v[1]!r}]",
        "[holes]",
        f"centres = [{centre!r}]",
        f"widths = [{width!r}]",
        "[horizon]",
        f"collisions = {n_star}",
        "[record]",
        'clocks = ["collisions"]',
        f"bins_per_decade = {base.bins_per_decade}",
        f"verify_samples = {verify_samples}",
        "",
    ])


def make_grid(base, grid):
    """The swept axes (at most two, in ``AXES`` order) and their values; ValueError if bad."""
    if base.kind != "escape":
        raise ValueError(f"sweep needs an escape scene, {base.name!r} is a {base.kind} scene")
    grid = {k: v for k, v in (grid or {}).items() if v is not None}
    unknown = sorted(set(grid) - set(AXES))
    if unknown:
        raise ValueError(f"unknown sweep axis {unknown[0]!r} (axes: {', '.join(AXES)})")
    if not grid:
        grid = {k: grid_values(*v, k) for k, v in DEFAULT_GRID.items()}
    if len(grid) > 2:
        raise ValueError("a sweep map has at most two axes of eps, --centre, --width;"
                         f" got {len(grid)}")
    axes = [a for a in AXES if a in grid]
    values = {}
    for a in axes:
        vals = [float(x) for x in grid[a]]
        if not vals:
            raise ValueError(f"--{a}: no values")
        values[a] = vals
    return axes, values


def plan_points(base, axes, values, n_star, particles, verify_samples):
    """Grid points in map order (y outer, x inner): dicts with eps, centre, width and
    ``scene`` (a Scene, or None with ``note`` saying why the point is skipped)."""
    fixed = {"eps": base.eps, "centre": base.hole_centres[0], "width": base.hole_widths[0]}
    xs = values[axes[0]]
    ys = values[axes[1]] if len(axes) > 1 else [None]
    count = len(xs) * len(ys)
    per_point = max(1, math.ceil(verify_samples / count))
    points = []
    for y in ys:
        for x in xs:
            p = dict(fixed)
            p[axes[0]] = x
            if len(axes) > 1:
                p[axes[1]] = y
            text = point_text(base, p["eps"], p["centre"], p["width"], n_star, particles,
                              per_point)
            try:
                p["scene"], p["note"] = parse_scene(text, "sweep point"), ""
            except ValueError as err:
                p["scene"], p["note"] = None, str(err).removeprefix("sweep point: ")
            points.append(p)
    return points


def sweep(base: Scene, out, *, grid=None, n_star=N_STAR, particles=PARTICLES, seed=None,
          verify_samples=VERIFY_SAMPLES, scheduler=None, threads=None, force=False,
          progress=True):
    """Run the escape-rate sweep of ``base`` over ``grid`` ({axis: values}, axes in ``AXES``,
    at most two; default ``DEFAULT_GRID``) into directory ``out``; returns the manifest.

    ``scheduler`` as in ``driver.run``. ValueError for bad input, RunFailed for a failed check.
    """
    n_star, particles = int(n_star), int(particles)
    if not 1 <= n_star <= 10**8:
        raise ValueError(f"--n-star must be in 1..1e8, got {n_star}")
    if particles < 1:
        raise ValueError(f"--particles must be >= 1, got {particles}")
    if int(verify_samples) < 1:
        raise ValueError(f"--verify-samples must be >= 1, got {verify_samples}")
    if seed is not None:
        if int(seed) < 0:
            raise ValueError(f"--seed must be >= 0, got {seed}")
        base = replace(base, seed=int(seed))
    axes, values = make_grid(base, grid)
    points = plan_points(base, axes, values, n_star, particles, int(verify_samples))
    live = [i for i, p in enumerate(points) if p["scene"] is not None]
    if not live:
        raise ValueError(f"no valid point in the sweep grid: {points[0]['note']}")
    if scheduler is not None:
        cluster.check_available()
    out = Path(out)
    rundir.check_out(out, False, force, resumable=False)  # refuse before creating anything
    new_dirs = rundir.missing_folders(out)
    session = {"scheduler": None, "workers": None, "worker_threads": None,
               "chunks_computed": 0}
    # connected before the directory exists; a sweep cannot be resumed, so one stopped by
    # anything but a failed check (recorded in its manifest) leaves nothing behind
    try:
        with Executor(scheduler, session) as execute, RunLock(out):
            rundir.prepare(out, False, force, resumable=False)
            try:
                return _sweep_locked(base, out, axes, values, points, live, n_star=n_star,
                                     particles=particles, threads=threads, execute=execute,
                                     session=session, progress=progress)
            except RunFailed:
                raise
            except BaseException:
                rundir.remove_run_files(out, SWEEP_FILES)
                raise
    except BaseException as err:
        if not isinstance(err, RunFailed):
            rundir.remove_new_folders(out, new_dirs)
        raise


SWEEP_FILES = (rundir.MANIFEST, "sweep.csv", "sample.csv", "escape-rate.png")


def _sweep_locked(base, out, axes, values, points, live, *, n_star, particles, threads,
                  execute, session, progress):
    plans = {i: make_plan(points[i]["scene"]) for i in live}
    jobs = [((i, k), (points[i]["scene"], base.seed, 0, k, particles, threads))
            for i in live for k in range(plans[i].chunks_per_experiment)]
    survivors = dict.fromkeys(live, 0)
    collisions = dict.fromkeys(live, 0)
    settled, samples, seen = 0, [], set()
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=len(jobs), unit="chunk", desc=f"sweep {base.name}")
    t0 = time.perf_counter()
    manifest = _manifest(base, axes, values, points, n_star, particles, session, "partial")
    rundir.write_json(out / rundir.MANIFEST, manifest)
    try:
        with closing(execute(jobs)) as results:
            for (i, k), result in results:
                check_result(result)
                if (i, k) in seen:
                    continue
                seen.add((i, k))
                session["chunks_computed"] += 1
                survivors[i] += int(result.counts.cens_n.sum())
                collisions[i] += result.counts.collisions
                settled += result.counts.settled
                samples.extend([i, *r] for r in result.rows)
                if result.bad:
                    row = dict(zip(("point", *rundir.sample_columns(base)), [i, *result.bad[0]],
                                   strict=True))
                    raise RunFailed(f"OVERSTEP at sweep point {i}: {len(result.bad)} sampled"
                                    " collision(s) where the fast flight time exceeds verify's"
                                    f" first root, first: {row}")
                if bar is not None:
                    bar.update()
    except RunFailed as err:
        manifest = _manifest(base, axes, values, points, n_star, particles, session, "failed")
        manifest["failure"] = str(err)
        rundir.write_json(out / rundir.MANIFEST, manifest)
        raise
    finally:
        if bar is not None:
            bar.close()
    rows = _rows(points, survivors, collisions, n_star, particles)
    rundir.write_csv(out / "sweep.csv", COLUMNS, rows)
    samples.sort(key=lambda r: (int(r[0]), int(r[1]), int(r[2]), int(r[3])))
    rundir.write_csv(out / "sample.csv", ("point", *rundir.sample_columns(base)),
                     [[*map(int, r[:5]), *map(repr, map(float, r[5:]))] for r in samples])
    plot_map(out / "escape-rate.png", base, axes, values, rows, n_star)
    manifest = _manifest(base, axes, values, points, n_star, particles, session, "complete")
    worst = max(samples, key=lambda r: r[11], default=None)
    manifest["verification"] = {
        "sampled": len(samples), "worst_error": worst[11] if worst else 0.0,
        "uncertain_settled": settled, "overstepped": 0,
        "error_unit": ERROR_UNIT}
    manifest["collisions"] = sum(collisions.values())
    manifest["wall_time_s"] = round(time.perf_counter() - t0, 3)
    rundir.write_json(out / rundir.MANIFEST, manifest)
    return manifest


def _rows(points, survivors, collisions, n_star, particles):
    rows = []
    for i, p in enumerate(points):
        head = [repr(p["eps"]), repr(p["centre"]), repr(p["width"]), particles, n_star]
        if p["scene"] is None:
            rows.append([*head, "", "", "", "", "", "", "", "", p["note"]])
            continue
        s = survivors[i]
        lo, hi = wilson(s, particles)
        prob = s / particles
        rate, rate_lo, rate_hi = (_rate(prob, n_star), _rate(float(hi), n_star),
                                  _rate(float(lo), n_star))
        rows.append([*head, s, repr(prob), repr(float(lo)), repr(float(hi)), repr(rate),
                     repr(rate_lo), repr(rate_hi), collisions[i], ""])
    return rows


def _rate(p, n_star):
    return math.inf if p <= 0 else -math.log(p) / n_star + 0.0  # + 0.0: no -0.0 at p = 1


def plot_map(path, base, axes, values, rows, n_star):
    """The heat map of the rate over the grid (blank: skipped or no survivor)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    xs = np.array(values[axes[0]])
    ys = np.array(values[axes[1]]) if len(axes) > 1 else np.array([0.0])
    rate = np.array([float(r[9]) if r[9] != "" else np.nan for r in rows]).reshape(len(ys),
                                                                                   len(xs))
    rate = np.ma.masked_invalid(rate)
    fig, ax = plt.subplots(figsize=(7, 5))
    mesh = ax.pcolormesh(_cell_edges(xs), _cell_edges(ys), rate, cmap="viridis", shading="flat")
    fig.colorbar(mesh, ax=ax, label=f"escape rate -ln P(n*)/n*, n* = {n_star}")
    ax.set_xlabel(LABELS[axes[0]])
    if len(axes) > 1:
        ax.set_ylabel(LABELS[axes[1]])
    else:
        ax.set_yticks([])
    fixed = {"eps": base.eps, "centre": base.hole_centres[0], "width": base.hole_widths[0]}
    rest = ", ".join(f"{a} = {fixed[a]:g}" for a in AXES if a not in axes)
    ax.set_title(f"{base.name}: escape-rate map ({rest})")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def _cell_edges(v):
    if len(v) == 1:
        return np.array([v[0] - 0.5, v[0] + 0.5])
    mid = (v[1:] + v[:-1]) / 2
    return np.concatenate([[2 * v[0] - mid[0]], mid, [2 * v[-1] - mid[-1]]])


def _manifest(base, axes, values, points, n_star, particles, session, status):
    return {
        "status": status,
        "kind": "sweep",
        "base_scene": {"name": base.name, "source": base.source},
        "seed": base.seed,
        "axes": {a: values[a] for a in axes},
        "fixed": {a: v for a, v in (("eps", base.eps), ("centre", base.hole_centres[0]),
                                    ("width", base.hole_widths[0])) if a not in axes},
        "points": len(points),
        "skipped": sum(p["scene"] is None for p in points),
        "n_star": n_star,
        "particles": particles,
        "rate": "-ln(P(n*))/n*, P(n*) = survivors of n* collisions / particles; 95% Wilson band",
        "session": session,
        "versions": versions(),
        "git": git(),
        "updated": now(),
    }
