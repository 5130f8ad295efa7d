"""``bouncer fit PATH... [--clock collisions|time] [--json] [--out DIR] [--jobs K]``.

Survival-law inference (``reports.stats``) for every curve of each PATH: a run directory (all its
curves, both clocks unless ``--clock``) or a CSV histogram ``lower,upper,count`` (clock ``time``,
continuous, unless ``--clock collisions``: integer values). ``--json`` prints only a JSON list,
one object per curve in input order; otherwise a table, and one PNG per curve in ``--out``, or
else beside the input: next to a CSV, in the folder RUN_DIR-fit beside a run directory (never
inside it: the run directory holds what its manifest records, and nothing else).
Unbounded interval ends and infinite values are JSON null.
Exit status: 0 ok, 2 bad input (one line on stderr).
"""

from __future__ import annotations

import json
import math
import os
import re
import sys
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

from reports.stats.analysis import analyse, best_law_text
from reports.stats.histogram import CLOCKS, read_csv_histogram, read_run

PROGRESS_FROM = 10  # curves; fewer run silently
STAGES_FROM = 1000  # bins: a curve this long reports its stages on stderr


def add_parser(subparsers):
    """Register ``fit`` on an argparse subparsers object."""
    p = subparsers.add_parser("fit", help="survival-law inference on escape histograms",
                              description=__doc__.split("\n\n")[1])
    _arguments(p)
    p.set_defaults(func=main)
    return p


def _arguments(p):
    p.add_argument("paths", nargs="+", metavar="PATH", help="run directory or CSV histogram")
    p.add_argument("--clock", choices=CLOCKS, help="only this clock (CSV: its meaning)")
    p.add_argument("--json", action="store_true", help="print only a JSON list to stdout")
    p.add_argument("--out", type=Path, help="folder for the PNGs (default: next to a CSV, the"
                   " folder RUN_DIR-fit beside a run directory)")
    p.add_argument("--jobs", type=int, default=min(2, os.cpu_count() or 1),
                   help="worker processes (default: min(2, cores))")


def load(paths, clock):
    """[(curve, default png folder)] of all inputs, in order; ValueError for bad input."""
    curves = []
    for path in map(Path, paths):
        if path.is_dir():
            found = read_run(path, clocks=(clock,) if clock else CLOCKS)
            if not found:
                raise ValueError(f"{path}: no curves for clock {clock}")
            beside = path.resolve().parent / f"{path.resolve().name}-fit"
            curves += [(c, beside) for c in found]
        elif path.exists():
            curves.append((read_csv_histogram(path, clock or "time"), path.parent))
        else:
            raise ValueError(f"{path}: no such file or directory")
    return curves


def _clean(value):
    """JSON-safe copy: inf/nan -> None, tuples -> lists, numpy scalars -> Python."""
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items() if not k.startswith("_")}
    if isinstance(value, list | tuple):
        return [_clean(v) for v in value]
    if hasattr(value, "item"):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _slug(text):
    return re.sub(r"[^A-Za-z0-9.=_-]+", "_", text).strip("_") or "curve"


def _work(item):
    curve, folder, out, plot = item
    label = f"fit: {Path(curve.source).name} {curve.curve} ({curve.clock})"
    say = (lambda text: print(f"{label}: {text}", file=sys.stderr, flush=True)) if len(
        curve.escapes) >= STAGES_FROM else None
    result = analyse(curve, progress=say)
    png = None
    if plot:
        from reports.stats.figure import plot_curve

        name = "-".join(_slug(s) for s in (curve.experiment, curve.curve, curve.clock) if s)
        png = Path(out or folder) / f"fit-{name}.png"
        png.parent.mkdir(parents=True, exist_ok=True)
        plot_curve(result, curve, png)
    result = _clean(result)
    return {"source": curve.source, **result, "png": str(png) if png else None}


def table(results):
    """Readable lines: per curve the best law with its parameters, window and regimes."""
    lines = []
    for r in results:
        regimes = " | ".join(f"{g['law']} {g['from']:g}-{g['to']:g}" for g in r["regimes"])
        lines.append(f"{Path(r['source']).name}  {r['curve']}  [{r['clock']}]  N={r['particles']}"
                     f"  best: {best_law_text(r)}"
                     f"  window [{r['window'][0]:g}, {r['window'][1]:g}]  regimes: {regimes}")
    return "\n".join(lines)


def main(args):
    """Run ``bouncer fit``; returns the exit status."""
    try:
        if args.jobs < 1:
            raise ValueError(f"--jobs must be >= 1, got {args.jobs}")
        curves = load(args.paths, args.clock)
        items = [(c, folder, args.out, not args.json) for c, folder in curves]
        progress = len(items) >= PROGRESS_FROM
        results = []
        if args.jobs > 1 and len(items) > 1:
            with ProcessPoolExecutor(max_workers=args.jobs) as pool:
                for i, r in enumerate(pool.map(_work, items, chunksize=4), start=1):
                    results.append(r)
                    if progress:
                        print(f"fit {i}/{len(items)}: {r['curve']} ({r['clock']})",
                              file=sys.stderr)
        else:
            for i, item in enumerate(items, start=1):
                results.append(_work(item))
                if progress:
                    print(f"fit {i}/{len(items)}: {item[0].curve} ({item[0].clock})",
                          file=sys.stderr)
    except (ValueError, OSError) as err:
        print(f"bouncer fit: error: {err}", file=sys.stderr)
        return 2
    if args.json:
        for r in results:
            r.pop("png")
        print(json.dumps(results, indent=1, allow_nan=False))
    else:
        print(table(results))
        for r in results:
            print(f"figure: {r['png']}")
    return 0
