#!/usr/bin/env bash
# Mutation testing. Not part of the default test run: it takes minutes.
#
#   scripts/mutation.sh [verify|runs|kernel|integrity|ensemble|solver|certify|all]     (default: all)
#
# verify, runs, kernel, integrity, certify: mutmut 3 on the pure-Python targets, configured by scripts/mutation/<group>.cfg
#   (copied to setup.cfg in a scratch copy of the worktree, so the worktree is never mutated).
# ensemble: fastpath/kernels/escape.py is numba-compiled, which mutmut's trampolines cannot be, so a
#   small AST driver (scripts/mutation/ensemble.py) applies one operator swap at a time to a
#   scratch copy and runs the ensemble tests with NUMBA_DISABLE_JIT=1.
# solver: the same driver (--group solver) on the scalar flight solvers (fastpath/elastic/concave.py,
#   tight_gap, lower_bound, flight, gap, short_flight, phase, collision);
#   MUTATION_FILES=fastpath/elastic/concave.py,...
#   restricts it to some of them.
#
# One worker, under nice -n 19: the machine is shared. MUTATION_NAMES=FILE runs the globs in FILE
# instead of scripts/mutation/<group>.names (e.g. only the functions added to a group). Scratch copies live under $MUTATION_DIR
# (default /tmp/bouncer-mutation); each group prints its survivors and a one-line score.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
work=${MUTATION_DIR:-/tmp/bouncer-mutation}
groups=${1:-all}
[ "$groups" = all ] && groups="verify runs kernel integrity ensemble solver certify"  # cheapest first

scratch_copy() {  # $1: destination; tracked and untracked-but-not-ignored files only
    rm -rf "$1" && mkdir -p "$1"
    (cd "$root" && git ls-files -co --exclude-standard -z | tar --null -cf - -T -) | tar -xf - -C "$1"
}

run_mutmut() {  # $1: group name (scripts/mutation/$1.cfg)
    local dest="$work/$1"
    scratch_copy "$dest"
    cp "$root/scripts/mutation/$1.cfg" "$dest/setup.cfg"
    cd "$dest"
    export NUMBA_CACHE_DIR="$work/numba-$1"
    local t0=$SECONDS
    # optional scripts/mutation/<group>.names (or the file $MUTATION_NAMES): mutant-name globs to
    # run, one a line
    local names=() names_file=${MUTATION_NAMES:-$root/scripts/mutation/$1.names}
    [ -f "$names_file" ] && mapfile -t names < "$names_file"
    nice -n 19 mutmut run --max-children 1 "${names[@]}" > mutmut-run.log 2>&1 || { tail -20 mutmut-run.log; return 1; }
    mutmut results --all true > results.txt 2>&1
    echo "== $1: wall $((SECONDS - t0)) s (log: $dest/mutmut-run.log)"
    python - results.txt <<'EOF'
import collections, sys  # "not checked": outside the group's .names selection
per = collections.defaultdict(collections.Counter)
for line in open(sys.argv[1]):
    if ":" not in line:
        continue
    name, status = (s.strip() for s in line.rsplit(":", 1))
    if status == "not checked":
        continue
    module = name.split(".x_")[0].split(".xǁ")[0]
    per[module][status] += 1
    if status not in ("killed",):
        print(f"   {status:10s} {name}")
for module, c in sorted(per.items()):
    n = sum(c.values())
    print(f"{module}: {n} mutants, {c['killed']} killed, {c['survived']} survived, "
          f"{c['timeout']} timeouts, other {n - c['killed'] - c['survived'] - c['timeout']}; "
          f"score {100 * c['killed'] / n:.1f}%")
EOF
    cd "$root"
}

for g in $groups; do
    case $g in
        verify|runs|kernel|integrity|certify) run_mutmut "$g" ;;
        ensemble)
            scratch_copy "$work/ensemble"
            nice -n 19 python "$root/scripts/mutation/ensemble.py" "$work/ensemble" ;;
        solver)
            scratch_copy "$work/solver"
            nice -n 19 python "$root/scripts/mutation/ensemble.py" --group solver \
                ${MUTATION_FILES:+--files "$MUTATION_FILES"} "$work/solver" ;;
        *) echo "unknown group: $g (verify, runs, kernel, integrity, ensemble, solver, certify, all)" >&2; exit 2 ;;
    esac
done
