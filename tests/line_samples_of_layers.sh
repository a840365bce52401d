#!/bin/sh
# Line samples on a mesh of layers. The water column of CASE (cases/water_dam_break.toml), its corner
# on a cell's corner (an initial soil fraction of whole cells, which the planar and the 3D shapes'
# sampling give alike), collapsing across a channel with slip front and back sides on two layers, is
# the planar collapse in every layer; so a line sampled at any depth z, between the layers' centres,
# gives the planar run's samples along the same x and y: u, v, p and the soil fraction to 1e-7 of
# their largest (the linear solvers' tolerance), w zero, and the header names x, y, z and w.
# Usage: line_samples_of_layers.sh GRANFLOW CASE DIR
set -f
g=$1 c=$2 d=$3
rm -rf "$d.planar" "$d.layers"
run() {
  out=$1; shift
  "$g" run "$c" -o "$out" --set 'mesh.cells=[56,24]' --set 'mesh.upper=[0.35,0.15]' --set time.end=0.05 \
    --set "initial.soil=[{shape='box', lower=[0.0, 0.0], upper=[0.0625, 0.125]}]" --set output.fields=false \
    --set output.checkpoints=false --set output.progress_seconds=0 "$@" > "$out.log" 2>&1 || { cat "$out.log"; exit 1; }
}
run "$d.planar" --set "output.line=[{name='floor', start=[0.0, 0.01], end=[0.35, 0.01], points=36}, \
{name='up', start=[0.03, 0.0], end=[0.03, 0.15], points=31}]"
run "$d.layers" --set 'mesh.cells=[56,24,2]' --set 'mesh.lower=[0,0,0]' --set 'mesh.upper=[0.35,0.15,0.1]' \
  --set 'physics.gravity=[0,-9.81,0]' --set "boundary.front={type='slip'}" --set "boundary.back={type='slip'}" \
  --set "output.line=[{name='floor', start=[0.0, 0.01, 0.03], end=[0.35, 0.01, 0.03], points=36}, \
{name='up', start=[0.03, 0.0, 0.09], end=[0.03, 0.15, 0.09], points=31}]"
exec /usr/bin/python3 - "$d.planar" "$d.layers" <<'PY'
import csv, sys
def read(path):
    with open(path) as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    return rows[0], [[float(v) for v in r] for r in rows[1:]]
failed = False
for name in ("floor", "up"):
    head2, planar = read(f"{sys.argv[1]}/{name}.csv")
    head3, layers = read(f"{sys.argv[2]}/{name}.csv")
    if head3[:7] != ["x", "y", "z", "u", "v", "w", "p"] or [h for h in head3 if h not in ("z", "w")] != head2:
        sys.exit(f"{name}: header {head3} against the planar {head2}")
    if len(planar) != len(layers):
        sys.exit(f"{name}: {len(layers)} points against {len(planar)}")
    for q in ("x", "y", "u", "v", "p", "soil_fraction"):
        a, b = head2.index(q), head3.index(q)
        scale = max(abs(r[a]) for r in planar) or 1.0
        apart = max(abs(r2[a] - r3[b]) for r2, r3 in zip(planar, layers))
        print(f"{name} {q}: largest {scale:.4g}, apart {apart:.2e}")
        failed |= not apart <= 1e-7 * scale
    w = max(abs(r[head3.index("w")]) for r in layers)
    print(f"{name} w: largest {w:.2e}")
    failed |= not w <= 1e-9
sys.exit(1 if failed else 0)
PY
