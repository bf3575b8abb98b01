#!/usr/bin/env bash
# One life scale for every level (issue 33 item 3; docs/fatigue.md §4 "One life scale for every
# level"; docs/decisions.md of the same name): fits the beam and elastic levels' constants of (6.31)
# to the complete level's lives and writes them, with the calibration's provenance, into the bundled
# fatigue card's "levels" (datasets/cards/fatigue-fritzson-1988.json; default_card() is built from it).
#   1. the cards of scripts/main.sh steps 3 and 6 (materials 2 and 1 fitted to their lab tables, so
#      they carry the data windows the complete level holds the damage at);
#   2. every drive of CALIBRATION and HELD_OUT at the complete level with those cards (Report I's
#      constants); a drive that does not complete is reported and left out;
#   3. per level, `fitcli life-fit --fix-n --fix-b` on one case per drive and mode whose observed life
#      is the complete level's life in that mode: σ0 alone, so each level reads the complete level's
#      law through one stress factor per mode, f = σ0_complete/σ0_level (docs/decisions.md says why n
#      and b are held). The beam level runs the bare drive file (its default: no cards, the Fritzson
#      laws' modulus), the elastic level the drive with the cards;
#   4. the card gets levels.beam and levels.elastic and provenance.level_calibration (drives, date,
#      fitlib commit, cards' sha256, factors, each drive's life ratio to the complete level);
#   5. the held-out drives at every level with the new card: the ratio table (bench_life prints the
#      same table: `bench_life calibration`).
# Takes ~1 min per drive on a loaded 2-core machine (the complete level). Rerun it when a level's
# stresses change (the complete level's reach, the elastic level's card reading) and commit the card.
# Env: BUILD_DIR (default build), OUT_DIR (work folder, default out/calibrate-levels), CALIBRATION,
# HELD_OUT (drive names in datasets/drives without .toml), CARD (the card to write, default the
# bundled one), REUSE_COMPLETE=1 (take step 2's lives from an earlier run's OUT_DIR/complete.txt).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
out=${OUT_DIR:-$root/out/calibrate-levels}
fitcli="$build/fitcli"
card=${CARD:-$root/datasets/cards/fatigue-fritzson-1988.json}
# Calibration: the light and heavy reference drives and every accelerated drive but acc-0500-torque-15;
# held out: the medium reference drive and acc-0500-torque-15 (a drive that does not complete at the
# complete level is left out of either and listed in the provenance).
accelerated=$(cd "$root/datasets/drives" && ls acc-0500-*.toml | sed 's/\.toml$//' | grep -v '^acc-0500-torque-15$' | tr '\n' ' ')
calibration=${CALIBRATION:-"ref-0500-light ref-0500-heavy $accelerated"}
held_out=${HELD_OUT:-"ref-0500-medium acc-0500-torque-15"}
mkdir -p "$out/scenes"
[ -x "$fitcli" ] || { echo "no $fitcli: build it first (cmake --build $build --target fitcli)" >&2; exit 2; }

echo "== 1. cards fitted to the lab tables (scripts/main.sh steps 3 and 6)"
data="$root/datasets/materials"
"$fitcli" fit --data "$data/material-2.csv" --model fritzson-iso --backend staged --no-progress \
  --schedule "$root/datasets/schedules/fritzson-iso.json" --name material-2 --out "$out/material-2.json" \
  > "$out/fit-material-2.txt" 2>&1
"$fitcli" fit --data "$data/material-1.csv" --model fritzson --backend staged --no-progress \
  --schedule "$root/datasets/schedules/fritzson.json" --name material-1 --out "$out/material-1.json" \
  > "$out/fit-material-1.txt" 2>&1

# scene NAME LEVEL [CARD]: the drive at LEVEL (beam: the bare drive, the level's default without
# cards; elastic, complete: with the cards of step 1), its life read with CARD (default: built in).
scene() {
  local s="$out/scenes/$1-$2${3:+-card}.toml"
  { cat "$root/datasets/drives/$1.toml"
    printf '\n# Written by scripts/calibrate-levels.sh.\n'
    [ "$2" = beam ] || printf '[belt.materials]\nbottom = "%s"\ncushion = "%s"\n\n' "$out/material-1.json" "$out/material-2.json"
    printf '[life]\nfidelity = "%s"\n' "$2"
    if [ -n "${3:-}" ]; then printf 'card = "%s"\n' "$3"; fi
  } > "$s"
  echo "$s"
}

# lives NAME LEVEL [CARD]: "N1 N2 governing" of fitcli life, or "failed <exit code>".
lives() {
  local s; s=$(scene "$@")
  local run="$out/runs/$1-$2${3:+-card}"
  if "$fitcli" -q life --scene "$s" --json --out-dir "$run" > "$run.json" 2> "$run.err"; then
    python3 - "$run.json" <<'EOF'
import json, sys
j = json.load(open(sys.argv[1]))
m = {x["mode"]: x["life_cycles"] for x in j["modes"]}
print(repr(m["radial_crack"]), repr(m["separation"]), j["governing_mode"])
EOF
  else echo "failed $?"; fi
}

echo "== 2. the complete level's lives (Report I's constants, the cards of step 1)"
mkdir -p "$out/runs"
if [ -n "${REUSE_COMPLETE:-}" ] && [ -s "$out/complete.txt" ]; then
  echo "(REUSE_COMPLETE: the lives of $out/complete.txt)"; cat "$out/complete.txt"
else
  : > "$out/complete.txt"
  for d in $calibration $held_out; do echo "$d $(lives "$d" complete)" | tee -a "$out/complete.txt"; done
fi

echo "== 3. each level with Report I's constants, and life-fit per level: sigma0 per mode, n and b held"
python3 -c "import json,sys; c=json.load(open(sys.argv[1])); c.pop('levels',None); json.dump(c,open(sys.argv[2],'w'),indent=2)" \
  "$card" "$out/complete-only.json"
for level in beam elastic; do
  csv="$out/life-tests-$level.csv"
  echo "case,scene,failure_mode,observed_cycles" > "$csv"
  : > "$out/$level.txt"
  for d in $calibration $held_out; do
    read -r n1 n2 _ < <(grep "^$d " "$out/complete.txt" | cut -d' ' -f2-)
    if [ "$n1" = failed ]; then echo "  $d: left out (the complete level did not complete)"; continue; fi
    echo "$d $(lives "$d" "$level" "$out/complete-only.json")" >> "$out/$level.txt"
    case " $held_out " in *" $d "*) continue ;; esac
    s=$(scene "$d" "$level")
    echo "$d-N1,$s,radial_crack,$n1" >> "$csv"
    echo "$d-N2,$s,separation,$n2" >> "$csv"
  done
  "$fitcli" -q life-fit --observed "$csv" --fix-n --fix-b --out "$out/fit-$level.json" > "$out/fit-$level.txt"
done

echo "== 4. the levels and the provenance into $card; each drive's life ratio to the complete level"
commit=$(git -C "$root" describe --always --dirty 2>/dev/null || echo unknown)
python3 - "$card" "$out" "$commit" "$calibration" "$held_out" <<'EOF'
import datetime, hashlib, json, sys
card_path, out, commit, calibration, held_out = sys.argv[1:]
card = json.load(open(card_path))
modes = ("radial_crack", "separation")

def read(path):  # drive -> {"N1", "N2", "governing"}, None where the run failed
    runs = {}
    for line in open(path):
        f = line.split()
        runs[f[0]] = None if f[1] == "failed" else {"N1": float(f[1]), "N2": float(f[2]), "governing": f[3]}
    return runs

complete = read(f"{out}/complete.txt")
sha = lambda p: hashlib.sha256(open(p, "rb").read()).hexdigest()
levels, record = {}, {}
print("%-22s %-8s %-9s %10s %10s %10s %-13s %s" % ("drive", "level", "set", "N1/compl", "N2/compl", "life/compl",
                                                 "governing", "mode"))
for level in ("beam", "elastic"):
    fitted = json.load(open(f"{out}/fit-{level}.json"))
    levels[level] = {m: {k: fitted["modes"][m][k] for k in ("sigma0_MPa", "n", "b_per_C", "stress_fidelity")}
                     for m in modes}
    factor = {m: card["modes"][m]["sigma0_MPa"] / levels[level][m]["sigma0_MPa"] for m in modes}
    ratios = {}
    for d, r in read(f"{out}/{level}.txt").items():
        c = complete[d]
        if r is None:
            ratios[d] = None
            continue
        # n held: the level's life with its own sigma0 is the life with Report I's times factor^-n
        after = [r[k] * factor[m] ** -card["modes"][m]["n"] for k, m in zip(("N1", "N2"), modes)]
        gov = modes[0] if after[0] < after[1] else modes[1]
        row = {"before": {"N1": r["N1"] / c["N1"], "N2": r["N2"] / c["N2"],
                          "life": min(r["N1"], r["N2"]) / min(c["N1"], c["N2"]), "governing": r["governing"]},
               "after": {"N1": after[0] / c["N1"], "N2": after[1] / c["N2"],
                         "life": min(after) / min(c["N1"], c["N2"]), "governing": gov}}
        ratios[d] = row
        for when in ("before", "after"):
            x = row[when]
            print("%-22s %-8s %-9s %10.3g %10.3g %10.3g %-13s %s" % (
                d, level, ("held out " if d in held_out.split() else "calib.   ") + when[0], x["N1"], x["N2"],
                x["life"], x["governing"], "same" if x["governing"] == c["governing"] else "differs"))
    record[level] = {"stress_factor": factor,
                     "rms_log10": {m: fitted["provenance"]["life_fit"][m]["rms_log10_error"] for m in modes},
                     "life_ratio_to_complete": ratios}
card["levels"] = levels
card["provenance"]["level_calibration"] = {
    "script": "scripts/calibrate-levels.sh",
    "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
    "fitlib_commit": commit,
    "method": "fitcli life-fit --fix-n --fix-b per level on one case per drive and mode, observed = the complete "
              "level's life in that mode (Report I's constants, the cards below); stress_factor = sigma0_complete / "
              "sigma0_level: the level's stress times it reads as the complete level's; life_ratio_to_complete: "
              "the level's lives over the complete level's with Report I's constants (before) and with the level's "
              "(after)",
    "cards": {"bottom": sha(f"{out}/material-1.json"), "cushion": sha(f"{out}/material-2.json"),
              "note": "scripts/main.sh steps 3 and 6 (datasets/materials/material-1.csv, material-2.csv)"},
    "beam_stresses": "the bare drive file (no cards: the Fritzson laws' modulus), the beam level's default",
    "calibration_drives": {d: complete[d] for d in calibration.split() if complete.get(d)},
    "held_out_drives": {d: complete.get(d) for d in held_out.split()},
    "not_completed_at_complete_level": [d for d in calibration.split() + held_out.split() if not complete.get(d)],
    "beam": record["beam"], "elastic": record["elastic"]}
open(card_path, "w").write(json.dumps(card, indent=2, ensure_ascii=False) + "\n")
for level in ("beam", "elastic"):
    print(level, "stress factors", record[level]["stress_factor"], "rms log10", record[level]["rms_log10"])
EOF

echo "== 5. check: the held-out drives at the beam and elastic levels read with the new card"
for d in $held_out; do
  for level in beam elastic; do echo "$d $level $(lives "$d" "$level" "$card")"; done
done
echo "== done: $card (commit it; a build of fitlib takes it into default_card()); work files in $out"
