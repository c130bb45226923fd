#!/usr/bin/env bash
# vsil sweep without an MPI launcher: a 100-task sweep (a product of axes, 99 cheap 32x32
# renders, plus one failing task) gets a row per task, the failure is reported in its row and
# on stderr while the other 99 complete (exit 3), the progress comes as milestone lines (not a
# terminal) up to "task 100/100"; a malformed sweep file stops before any render with one line
# naming the file (exit 2) and writes no result file, nor does an --out-dir naming the result
# file. With mpirun (where found, $2), the same
# sweep over 3 ranks gives the same rows, spread over the ranks.
set -uo pipefail
vsil=$1
mpirun=${2:-}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "sweep_test: $*" >&2; exit 1; }

cat >"$dir/sweep.json" <<'JSON'
{"render": {"input": "gen:spheres:32", "size": "32x32"},
 "axes": {"view": ["0,10", "11,20", "22,10", "33,0", "44,-10", "55,10", "66,20", "77,30",
                   "88,-20", "99,10", "110,0", "121,10", "132,20", "143,-10", "154,10",
                   "165,0", "176,20", "187,10", "198,-10", "209,0", "220,10", "231,20",
                   "242,30", "253,-20", "264,10", "275,0", "286,10", "297,20", "308,-10",
                   "319,10", "330,0", "341,20", "352,10"],
          "width": [1, 2, 3]},
 "tasks": [{"input": "missing.nrrd"}]}
JSON
"$vsil" sweep "$dir/sweep.json" --json "$dir/one.json" --csv "$dir/one.csv" 2>"$dir/err"
rc=$?
[[ $rc == 3 ]] || fail "a sweep with one failing task exited $rc, not 3: $(cat "$dir/err")"
grep -q "missing.nrrd" "$dir/err" || fail "the failing task's error is not reported: $(cat "$dir/err")"
# Progress: milestone lines (stderr is no terminal here), the last one complete with the failure.
grep -Eq "task 100/100 \[#{20}\] 1 failed, [0-9.]+ tasks/s, 0 s left" "$dir/err" ||
  fail "no final progress line: $(cat "$dir/err")"
(($(grep -c "task [0-9]*/100 \[" "$dir/err") >= 5)) || fail "fewer than 5 progress lines: $(cat "$dir/err")"
check_rows() {
  /usr/bin/python3 - "$1" <<'PY' || exit 1
import json, sys
document = json.load(open(sys.argv[1]))
rows = document["rows"]
assert len(rows) == 100, f"{len(rows)} rows, not 100"
assert sorted(r["task"] for r in rows) == list(range(100)), "task indices are not 0..99"
failed = [r for r in rows if r["status"] != "ok"]
assert len(failed) == 1 and failed[0]["task"] == 99, f"failed rows: {failed}"
assert "missing.nrrd" in failed[0]["error"], failed[0]
ok = [r for r in rows if r["status"] == "ok"]
assert all(r["pixels"]["silhouette"] > 0 for r in ok), "a completed task drew no silhouette"
PY
}
check_rows "$dir/one.json"
[[ $(wc -l <"$dir/one.csv") == 101 ]] || fail "the CSV does not hold a header and 100 rows"

echo '{"axes": {"bogus": [1]}}' >"$dir/bad.json"
"$vsil" sweep "$dir/bad.json" --json "$dir/bad-out.json" 2>"$dir/err"
rc=$?
[[ $rc == 2 ]] || fail "a malformed sweep file exited $rc, not 2"
[[ $(wc -l <"$dir/err") == 1 ]] && grep -q "bad.json" "$dir/err" ||
  fail "a malformed sweep file does not get one line naming it: $(cat "$dir/err")"
[[ ! -e $dir/bad-out.json ]] || fail "a malformed sweep file left a result file"

# The axes in the file's order, the last fastest (they were taken in alphabetical order); two
# spellings of one flag are refused (they made two axes, and "swept" named a value not rendered).
echo '{"render": {"input": "gen:sphere:16", "size": "16x16"},
       "axes": {"zoom": [1, 2], "view": ["0,0", "90,0"]}}' >"$dir/order.json"
"$vsil" sweep "$dir/order.json" --json "$dir/order-out.json" --quiet 2>"$dir/err" ||
  fail "the ordered sweep failed: $(cat "$dir/err")"
/usr/bin/python3 - "$dir/order-out.json" <<'PY' || exit 1
import json, sys
rows = sorted(json.load(open(sys.argv[1]))["rows"], key=lambda r: r["task"])
swept = [(r["swept"]["zoom"], r["swept"]["view"]) for r in rows]
assert swept == [(1, "0,0"), (1, "90,0"), (2, "0,0"), (2, "90,0")], swept
PY
# Numbers in a sweep file as the command line reads them: 010 is ten (CLI11 alone read the octal
# 8 while the row recorded --stride 010), hexadecimal is refused in that task's row.
echo '{"render": {"input": "gen:sphere:40", "size": "16x16"},
       "axes": {"stride": ["010", "10", "0x8"]}}' >"$dir/decimal.json"
"$vsil" sweep "$dir/decimal.json" --json "$dir/decimal-out.json" --quiet 2>"$dir/err"
[[ $? == 3 ]] || fail "the decimal sweep did not fail its hexadecimal task: $(cat "$dir/err")"
/usr/bin/python3 - "$dir/decimal-out.json" <<'PY' || exit 1
import json, sys
rows = sorted(json.load(open(sys.argv[1]))["rows"], key=lambda r: r["task"])
assert rows[0]["status"] == rows[1]["status"] == "ok", rows
assert rows[0]["slices"] == rows[1]["slices"], (rows[0]["slices"], rows[1]["slices"])
assert rows[2]["status"] != "ok" and "hexadecimal" in rows[2]["error"], rows[2]
PY
echo '{"axes": {"width_near": [1, 2], "width-near": [3, 4]}}' >"$dir/twice.json"
"$vsil" sweep "$dir/twice.json" --json "$dir/twice-out.json" 2>"$dir/err"
rc=$?
[[ $rc == 2 ]] || fail "two spellings of one flag exited $rc, not 2"
grep -qx "vsil: $dir/twice.json: axes: width-near: names the same flag as width_near: give one" \
  "$dir/err" || fail "two spellings of one flag: $(cat "$dir/err")"
# A flag both in "render" and swept: render's value no task would use (it was dropped silently).
echo '{"render": {"zoom": 2}, "axes": {"zoom": [1, 3]}}' >"$dir/both.json"
"$vsil" sweep "$dir/both.json" --json "$dir/both-out.json" 2>"$dir/err"
rc=$?
[[ $rc == 2 ]] || fail "a flag in render and in axes exited $rc, not 2"
grep -qx "vsil: $dir/both.json: axes: zoom: is swept, and \"render\" sets it too (zoom), which no task would use: give it in one place" \
  "$dir/err" || fail "a flag in render and in axes: $(cat "$dir/err")"
[[ ! -e $dir/both-out.json ]] || fail "a refused sweep wrote its result"

# An --out-dir naming a result file (either spelling) is refused before any render, as two
# outputs naming one file are (it rendered every task, then failed with "Is a directory").
(cd "$dir" && "$vsil" sweep sweep.json --json r.json --out-dir ./r.json 2>err)
rc=$?
[[ $rc == 2 ]] || fail "--out-dir naming the --json file exited $rc, not 2"
grep -qx "vsil: --out-dir ./r.json: names the same file as --json r.json; give each output its own file" \
  "$dir/err" || fail "--out-dir naming the --json file: $(cat "$dir/err")"
[[ ! -e $dir/r.json ]] || fail "--out-dir naming the --json file left r.json"

# An --out-dir whose parent is missing is refused before any render, as animate's (it was
# created whole, as mkdir -p would, so a typo in its path went unnoticed).
"$vsil" sweep "$dir/sweep.json" --json "$dir/nested.json" --out-dir "$dir/no/such/images" \
  2>"$dir/err"
rc=$?
[[ $rc == 2 ]] || fail "--out-dir with a missing parent exited $rc, not 2"
grep -qx "vsil: --out-dir $dir/no/such/images: folder $dir/no/such does not exist" "$dir/err" ||
  fail "--out-dir with a missing parent: $(cat "$dir/err")"
[[ ! -e $dir/no && ! -e $dir/nested.json ]] || fail "--out-dir with a missing parent wrote"

if [[ -n $mpirun ]]; then
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 \
    "$mpirun" --oversubscribe -np 3 "$vsil" sweep "$dir/sweep.json" --json "$dir/three.json" \
    2>"$dir/err"
  rc=$?
  [[ $rc == 3 ]] || fail "under mpirun -np 3 the sweep exited $rc, not 3: $(cat "$dir/err")"
  check_rows "$dir/three.json"
  grep -Eq "task 100/100 \[#{20}\] 1 failed" "$dir/err" ||
    fail "under mpirun -np 3: no final progress line: $(cat "$dir/err")"
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
