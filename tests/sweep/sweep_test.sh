#!/usr/bin/env bash
# vsil sweep without an MPI launcher: every task of a product of axes plus one failing task
# gets its row, the failure is reported and the rest complete (exit 3); a malformed sweep file
# stops before any render with one line naming the file (exit 2) and writes no result file.
# With mpirun (where found, $2), the same sweep over 3 ranks gives the same rows.
set -uo pipefail
vsil=$1
mpirun=${2:-}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "sweep_test: $*" >&2; exit 1; }

cat >"$dir/sweep.json" <<'JSON'
{"render": {"input": "gen:spheres:32", "size": "32x32"},
 "axes": {"view": ["0,10", "30,20", "60,10", "90,0", "120,-10"], "width": [1, 2, 3, 4]},
 "tasks": [{"input": "missing.nrrd"}]}
JSON
"$vsil" sweep "$dir/sweep.json" --json "$dir/one.json" --csv "$dir/one.csv" --quiet 2>"$dir/err"
rc=$?
[[ $rc == 3 ]] || fail "a sweep with one failing task exited $rc, not 3: $(cat "$dir/err")"
grep -q "missing.nrrd" "$dir/err" || fail "the failing task's error is not reported: $(cat "$dir/err")"
check_rows() {
  /usr/bin/python3 - "$1" <<'PY' || exit 1
import json, sys
rows = json.load(open(sys.argv[1]))["rows"]
assert len(rows) == 21, f"{len(rows)} rows, not 21"
assert sorted(r["task"] for r in rows) == list(range(21)), "task indices are not 0..20"
failed = [r for r in rows if r["status"] != "ok"]
assert len(failed) == 1 and failed[0]["task"] == 20, f"failed rows: {failed}"
assert "missing.nrrd" in failed[0]["error"], failed[0]
PY
}
check_rows "$dir/one.json"
[[ $(wc -l <"$dir/one.csv") == 22 ]] || fail "the CSV does not hold a header and 21 rows"

echo '{"axes": {"bogus": [1]}}' >"$dir/bad.json"
"$vsil" sweep "$dir/bad.json" --json "$dir/bad-out.json" 2>"$dir/err"
rc=$?
[[ $rc == 2 ]] || fail "a malformed sweep file exited $rc, not 2"
[[ $(wc -l <"$dir/err") == 1 ]] && grep -q "bad.json" "$dir/err" ||
  fail "a malformed sweep file does not get one line naming it: $(cat "$dir/err")"
[[ ! -e $dir/bad-out.json ]] || fail "a malformed sweep file left a result file"

if [[ -n $mpirun ]]; then
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 \
    "$mpirun" --oversubscribe -np 3 "$vsil" sweep "$dir/sweep.json" --json "$dir/three.json" --quiet \
    2>"$dir/err"
  rc=$?
  [[ $rc == 3 ]] || fail "under mpirun -np 3 the sweep exited $rc, not 3: $(cat "$dir/err")"
  check_rows "$dir/three.json"
  /usr/bin/python3 - "$dir/one.json" "$dir/three.json" <<'PY' || exit 1
import json, sys
one, three = (json.load(open(p))["rows"] for p in sys.argv[1:])
key = lambda r: r["task"]
for a, b in zip(sorted(one, key=key), sorted(three, key=key)):
    assert a["status"] == b["status"] and a.get("pixels") == b.get("pixels"), (a, b)
assert len({r["rank"] for r in three}) > 1, "one rank ran every task under mpirun -np 3"
PY
fi
echo "sweep_test: ok"
