"""``bouncer fit PATH... [--clock collisions|time] [--json] [--out DIR] [--jobs K]``.

Survival-law inference (``reports.stats``) for every curve of each PATH: a run directory (all its
curves, both clocks unless ``--clock``) or a CSV histogram ``lower,upper,count`` (clock ``time``,
continuous, unless ``--clock collisions``: integer values). ``--json`` prints only a JSON list,
one object per curve in input order; otherwise a table, and one PNG per curve in ``--out``, or
else beside the input: next to a CSV, in the folder RUN_DIR-fit beside a run directory (never
inside it: the run directory holds what its manifest records, and nothing else).
Unbounded interval ends and infinite values are JSON null; in the table an interval end the
data do not bound is printed as such (``[0.53, unbounded]``).

PNG names: ``fit-CURVE-CLOCK.png`` (a run's curve names are its own: no experiment repeated);
where two inputs of one command would give one name, the input's name comes first, then a
number. Every curve is analysed before any figure is written, and the figures are written
atomically: a command that fails (bad input, a curve no law fits, a folder it cannot write)
leaves none of its files behind.
Exit status: 0 ok, 2 bad input or a file it cannot write (one line on stderr).
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
import re
import sys
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from pathlib import Path

from reports.cli import MAX_LINE
from reports.runs.echo import clip, plain, plain_text
from reports.runs.rundir import missing_folders, os_error_text, write_atomic
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
        try:
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
        except csv.Error as err:  # a field over csv's size limit, a NUL byte
            raise ValueError(f"{path}: not readable as CSV ({clip(str(err))})") from None
    return curves


def _clean(value):
    """JSON-safe copy: inf/nan -> None, tuples -> lists, numpy scalars -> Python."""
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items() if not k.startswith("_")}
    if isinstance(value, list | tuple):
        return [_clean(v) for v in value]
    value = plain(value)
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _slug(text):
    return re.sub(r"[^A-Za-z0-9.=_-]+", "_", text).strip("_") or "curve"


def _work(item):
    """Analyse one curve; with ``plot`` also draw its figure, as PNG bytes (written by the
    caller once every curve is analysed)."""
    curve, plot = item
    label = f"fit: {Path(curve.source).name} {curve.curve} ({curve.clock})"
    say = (lambda text: print(f"{label}: {text}", file=sys.stderr, flush=True)) if len(
        curve.escapes) >= STAGES_FROM else None
    result = analyse(curve, progress=say)
    png = None
    if plot:
        from reports.stats.figure import plot_curve

        buffer = io.BytesIO()
        plot_curve(result, curve, buffer)
        png = buffer.getvalue()
    return {"source": curve.source, **_clean(result)}, png


def figure_paths(curves, out):
    """The PNG path of each (curve, default folder): ``fit-CURVE-CLOCK.png`` in ``out`` or the
    default folder; names that two inputs share get the input's name first, then a number."""
    def name(curve, source):
        parts = (Path(curve.source).stem if source else "", curve.curve, curve.clock)
        return "fit-" + "-".join(_slug(p) for p in parts if p)

    folders = [Path(out) if out else folder for _, folder in curves]
    plain_names = [folder / name(c, False) for (c, _), folder in zip(curves, folders,
                                                                      strict=True)]
    paths, taken = [], set()
    for (curve, _), folder, first in zip(curves, folders, plain_names, strict=True):
        path = first if plain_names.count(first) == 1 else folder / name(curve, True)
        stem, n = path, 1
        while path in taken:
            n += 1
            path = stem.with_name(f"{stem.name}-{n}")
        taken.add(path)
        paths.append(path.with_name(path.name + ".png"))
    return paths


def write_figures(paths, pngs):
    """Write each PNG atomically, making the folders they need; if any write fails, remove
    what this call wrote (files and folders) and raise the OSError."""
    written, made = [], []
    try:
        for path, png in zip(paths, pngs, strict=True):
            new = missing_folders(path.parent)
            path.parent.mkdir(parents=True, exist_ok=True)
            made += new
            write_atomic(path, png)
            written.append(path)
    except BaseException:
        for path in written:
            path.unlink(missing_ok=True)
        for folder in made:  # deepest first
            try:
                folder.rmdir()
            except OSError:
                pass
        raise


def table(results):
    """Readable lines: per curve the best law with its parameters, window and regimes."""
    lines = []
    for r in results:
        regimes = " | ".join(f"{g['law']} {g['from']:g}-{g['to']:g}" for g in r["regimes"])
        lines.append(f"{Path(r['source']).name}  {r['curve']}  [{r['clock']}]  N={r['particles']}"
                     f"  best: {best_law_text(r)}"
                     f"  window [{r['window'][0]:g}, {r['window'][1]:g}]  regimes: {regimes}")
    return "\n".join(lines)


def _analyse_all(curves, plot, jobs):
    items = [(c, plot) for c, _ in curves]
    progress = len(items) >= PROGRESS_FROM
    done = []
    if jobs > 1 and len(items) > 1:
        with ProcessPoolExecutor(max_workers=jobs) as pool:
            for i, r in enumerate(pool.map(_work, items, chunksize=4), start=1):
                done.append(r)
                if progress:
                    print(f"fit {i}/{len(items)}: {r[0]['curve']} ({r[0]['clock']})",
                          file=sys.stderr)
    else:
        for i, item in enumerate(items, start=1):
            done.append(_work(item))
            if progress:
                print(f"fit {i}/{len(items)}: {item[0].curve} ({item[0].clock})",
                      file=sys.stderr)
    return done


def _error(text):
    """One line on stderr (plain numbers, bounded length); exit status 2."""
    line = clip(plain_text(f"bouncer fit: error: {text}".replace("\n", " ")), MAX_LINE)
    print(line, file=sys.stderr)
    return 2


def main(args):
    """Run ``bouncer fit``; returns the exit status."""
    try:
        if args.jobs < 1:
            raise ValueError(f"--jobs must be >= 1, got {args.jobs}")
        curves = load(args.paths, args.clock)
        done = _analyse_all(curves, not args.json, args.jobs)
        results = [r for r, _ in done]
        if not args.json:
            paths = figure_paths(curves, args.out)
            write_figures(paths, [png for _, png in done])
            for r, path in zip(results, paths, strict=True):
                r["png"] = str(path)
    except ValueError as err:
        return _error(str(err))
    except OSError as err:
        return _error(os_error_text(err))
    except BrokenProcessPool:
        return _error("a worker process died (out of memory?); try --jobs 1")
    if args.json:
        print(json.dumps(results, indent=1, allow_nan=False))
    else:
        print(table(results))
        for r in results:
            print(f"figure: {r['png']}")
    return 0
