"""Move the record of how a run was made out of its manifest.json into provenance.json.

    python scripts/split_provenance.py RUN_DIR...

manifest.json holds only what ``bouncer verify`` audits (``reports.runs.manifest``); package
versions, the git commit, threads, the cluster session, timestamps and timings are a record
kept in provenance.json, whose SHA-256 the manifest holds. A manifest that still holds those
fields is refused by its schema; this rewrites it (atomically) into the two files. The
timings keep their values: ``compute_s`` is the recorded wall time, ``compile_s`` is null (it
was not timed apart). Nothing else of the run directory is touched.
"""

import json
import sys
from pathlib import Path

from reports.runs import rundir
from reports.runs.manifest import PROVENANCE_SCHEMA, SCHEMA, check

RECORD = ("versions", "git", "threads", "session", "started", "updated", "finished")


def split(run_dir):
    run_dir = Path(run_dir)
    old = json.loads((run_dir / rundir.MANIFEST).read_text(encoding="utf-8"))
    if "versions" not in old:
        return f"{run_dir}: already split"
    record = {key: old[key] for key in RECORD}
    record.update(compile_s=None, compute_s=old["wall_time_s"],
                  collisions_per_s=old["collisions_per_s"])
    check(record, PROVENANCE_SCHEMA, run_dir / rundir.PROVENANCE)
    manifest = {key: old[key] for key in SCHEMA["properties"] if key in old}
    manifest["hashes"] = dict(sorted({**old["hashes"], rundir.PROVENANCE:
                                      rundir.sha256_bytes(_text(record))}.items()))
    check(manifest, SCHEMA, run_dir / rundir.MANIFEST)
    rundir.write_atomic(run_dir / rundir.PROVENANCE, _text(record))
    rundir.write_atomic(run_dir / rundir.MANIFEST, _text(manifest))
    return f"{run_dir}: split"


def _text(obj):
    return json.dumps(obj, indent=2) + "\n"  # as rundir.write_json writes it


if __name__ == "__main__":
    for path in sys.argv[1:]:
        print(split(path))
