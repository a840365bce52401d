#!/bin/sh
# Soil materials on a mesh of layers, from the command line. CASE (cases/narrow_channel_3d.toml) with a
# weak lower layer across half the channel (a solid of its own material under the planar block):
# check says each soil's volume; a run writes the weak soil's volume fraction among the fields; and a
# run restarted from its checkpoint ends where a run straight through ends, to the byte (the shares
# are in the checkpoint).
# Usage: materials_of_layers.sh GRANFLOW CASE DIR
set -f
g=$1 c=$2 d=$3
rm -rf "$d.restarted" "$d.straight"
weak='soil.materials=[{name="weak", friction_angle=10.0}]'
shapes='initial.soil=[{shape="box", lower=[0,0], upper=[0.2,0.1]}, {shape="box", lower=[0,0,0], upper=[0.2,0.05,0.02], material="weak"}]'
out=$("$g" check "$c" --set "$weak" --set "$shapes" 2>&1) || { echo "$out"; exit 1; }
echo "$out" | grep -q "initial soil 0.0008 m^3, of which the rheology's own soil 0.0006, weak 0.0002)" || { echo "$out"; exit 1; }
run() {
  out=$1 end=$2; shift 2
  "$g" run "$c" -o "$out" --set 'mesh.cells=[30,10,4]' --set time.end="$end" --set output.interval=0.02 \
    --set output.progress_seconds=0 --set "$weak" --set "$shapes" "$@" > "$out.log" 2>&1 || { cat "$out.log"; exit 1; }
}
run "$d.restarted" 0.04
grep -a -q 'Name="soil_fraction_weak"' "$d.restarted/fields_00002.vtr" || { echo "no soil_fraction_weak in the fields"; exit 1; }
run "$d.restarted" 0.06 --restart
run "$d.straight" 0.06
cmp "$d.restarted/checkpoint/fields.bin" "$d.straight/checkpoint/fields.bin" || exit 1
tail -1 "$d.restarted/history.csv" | cut -d, -f1-4
