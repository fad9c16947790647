#!/usr/bin/env bash
# `make bench`: rays traced per second (camera + bounce + shadow) and samples per second of
# path_mis on the 202k-triangle dragon, with 1 and 2 threads; the median of 3 runs each.
# Scene loading (mesh import, BVH build) is excluded: the renderer times the render loop.
set -euo pipefail
renderer=${1:-build/bin/renderer}
scene=configs/scenes/dragon_bench.json
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

median() { sort -g | sed -n 2p; }

declare -A rays samples
for threads in 1 2; do
  for run in 1 2 3; do
    line=$("$renderer" render "$scene" --threads "$threads" --no-preview --out "$out/b.exr" 2>&1 | tail -1)
    echo "  $line" | sed "s|$out/||" >&2
    echo "$line" | sed -E 's/.*\(([0-9.]+) Mrays\/s, ([0-9.]+) Msamples\/s.*/\1 \2/' >> "$out/t$threads"
  done
  rays[$threads]=$(cut -d' ' -f1 "$out/t$threads" | median)
  samples[$threads]=$(cut -d' ' -f2 "$out/t$threads" | median)
done
echo "dragon_vrip_res2 (202,520 triangles), path_mis, 512x384, 24 spp, median of 3 runs:"
for threads in 1 2; do
  echo "  $threads thread(s): ${rays[$threads]} Mrays/s, ${samples[$threads]} Msamples/s"
done
awk -v a="${rays[1]}" -v b="${rays[2]}" 'BEGIN { printf "  2-thread speed-up: %.2fx\n", b / a }'
