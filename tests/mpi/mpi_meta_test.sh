#!/usr/bin/env bash
# `mpirun -np N vsil render --meta-out` (issue 35): rank 0's metadata holds every rank's numbers
# in mpi.per_rank: one entry per rank in rank order, the frame, the slab's render and the
# combining (reduce_ms <= frame_ms, render + reduce <= frame), the bytes held (at least the
# slab's own samples, less than the whole volume's samples and texture) and the peak resident
# memory (at least what it holds). Usage: mpi_meta_test.sh VSIL MPIEXEC
set -euo pipefail
vsil=$1
mpiexec=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

for n in 2 3; do
  "$mpiexec" --oversubscribe -np "$n" "$vsil" render gen:spheres:64 --technique mip \
    --size 64x64 --view 37,-23 --out "$work/many.png" --meta-out "$work/many.json" >/dev/null
  /usr/bin/python3 - "$work/many.json" "$n" <<'PY'
import json, sys
meta = json.load(open(sys.argv[1]))
n = int(sys.argv[2])
mpi = meta["mpi"]
ranks = mpi["per_rank"]
assert len(ranks) == n, f"{len(ranks)} per_rank entries, not {n}"
assert [r["rank"] for r in ranks] == list(range(n)), [r["rank"] for r in ranks]
whole_samples = 64 * 64 * 64 * 4  # float32 samples
for r, (z0, z1) in zip(ranks, mpi["slabs"]):
    where = f"rank {r['rank']}: {r}"
    assert r["frame_ms"] > 0 and r["frame_cpu_ms"] > 0, where
    assert 0 <= r["render_ms"] <= r["frame_ms"], where
    assert 0 <= r["reduce_ms"] <= r["frame_ms"], where
    assert r["render_ms"] + r["reduce_ms"] <= r["frame_ms"] * 1.001 + 0.01, where
    own = 64 * 64 * (z1 - z0)
    # Its own samples at one byte or more each; less than the whole volume's samples + texture.
    assert own <= r["held_bytes"] < 2 * whole_samples, where
    assert r["peak_rss_bytes"] >= r["held_bytes"], where
    assert r["peak_rss_bytes"] < 8 << 30, where
    assert r["checked_bytes"] > 0, where
PY
done
echo "mpi metadata: per_rank plausible for -np 2, 3"
