#!/usr/bin/env bash
# The main job on the bundled data: installs what is missing, builds fitcli, then
#   fit → card → plot → FE export   (pyvisco's master curve and a synthetic WLF table)
#   staged fit of the thesis's damage model → card → modulus surface
#   belt load cycle of a reference drive
#   lab tables → fitted cards (materials 1 and 2) → fatigue life of the reference drive
#   (the elastic level, then the complete level with the cards' full models)
# Results land in OUT_DIR (default out/).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${OUT_DIR:-$root/out}
"$root/scripts/install-deps.sh"
export BUILD_DIR=${BUILD_DIR:-$root/build}
cmake -S "$root" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD_DIR" -j "$(nproc)" --target fitcli
fitcli="$BUILD_DIR/fitcli"
mkdir -p "$out"
data="$root/datasets/materials"

echo "== 1. Prony card from pyvisco's master curve (smooth spectrum, smoothness chosen by GCV; quality verdict shown)"
"$fitcli" fit --data "$data/pyvisco-freq-master.csv" --format pyvisco --model prony --terms auto \
  --reference-c -5 --name pyvisco-master --out "$out/pyvisco-master.json"
grid=$(/usr/bin/python3 -c "print(','.join(repr(10**(k/10)) for k in range(-120, 141)))")
"$fitcli" eval --card "$out/pyvisco-master.json" --mode uniaxial --frequency-hz "$grid" \
  --out "$out/pyvisco-master-curve.csv"
"$fitcli" plot --data "$data/pyvisco-freq-master.csv" --format pyvisco --card "$out/pyvisco-master.json" \
  --title "pyvisco master curve: data and Prony card" --out "$out/pyvisco-master.png"
"$fitcli" export --card "$out/pyvisco-master.json" --format abaqus --out "$out/pyvisco-master.inp"
echo "Abaqus keywords written to $out/pyvisco-master.inp"

echo "== 2. Prony + WLF card from a synthetic shear table of known truth"
"$fitcli" fit --data "$data/synthetic-prony-wlf.csv" --model prony --terms 6 --temperature-law wlf \
  --reference-c 23 --name synthetic-prony-wlf --out "$out/synthetic-prony-wlf.json"
# Its isotherms (-20 to 80 degC, 0.1-100 Hz) reach 1e-4 to 1e8 Hz at 23 degC through the WLF law.
wlf_grid=$(/usr/bin/python3 -c "print(','.join(repr(10**(k/10)) for k in range(-40, 81)))")
"$fitcli" eval --card "$out/synthetic-prony-wlf.json" --frequency-hz "$wlf_grid" --temperature-c 23 \
  --out "$out/synthetic-prony-wlf-curve.csv"

echo "== 3. The thesis's damage model: staged fit of material 2 (isotropic cushion rubber)"
"$fitcli" fit --data "$data/material-2.csv" --model fritzson-iso --backend staged \
  --schedule "$root/datasets/schedules/fritzson-iso.json" --name material-2 --out "$out/material-2.json"

echo "== 4. Modulus surface over (amplitude, frequency, temperature) from that card"
"$fitcli" surface grid --card "$out/material-2.json" --mode shear --orientation 12 \
  --amplitude 0.005,0.015,0.045 --frequency-hz 3,34,60 --temperature-c 23,60,100 \
  --out "$out/material-2-grid.csv" --surface-out "$out/material-2-surface.json"

echo "== 5. Belt load cycle of the reference drive (only the effects the scene asks for)"
"$fitcli" belt --scene "$root/datasets/drives/ref-0500-medium.toml" --out-dir "$out/belt" --plot "$out/belt.png"

echo "== 6. Fatigue life: lab table -> fitted card -> life (material 1 bottom, material 2 cushion)"
"$fitcli" fit --data "$data/material-1.csv" --model fritzson --backend staged \
  --schedule "$root/datasets/schedules/fritzson.json" --name material-1 --out "$out/material-1.json"
# A copy of the reference drive with the fitted cards; life.json names each card with its sha256,
# and each card's provenance names its lab table with its sha256.
scene="$out/ref-0500-medium-fitted-cards.toml"
cat "$root/datasets/drives/ref-0500-medium.toml" - > "$scene" <<EOF

# Written by scripts/main.sh: the cards fitted in steps 3 and 6.
[belt.materials]
bottom = "material-1.json"
cushion = "material-2.json"

[life]
card = "$root/datasets/cards/fatigue-fritzson-1988.json"
EOF
"$fitcli" life --scene "$scene" --out-dir "$out/life" --plot "$out/life.png"

echo "== 7. The same drive at the complete level: the fitted cards' full models (damage held at what their tests reached)"
complete="$out/ref-0500-medium-fitted-cards-complete.toml"
sed 's/^\[life\]$/[life]\nfidelity = "complete"/' "$scene" > "$complete"
"$fitcli" life --scene "$complete" --out-dir "$out/life-complete" --plot "$out/life-complete.png"

echo "== done: cards, curves, plots, surface, load history and lives (figures: $out/life.png, $out/life-complete.png) in $out"
