#!/usr/bin/env bash
# Rebuilds every shipped network in resources/models/ from the Bandai Namco Research motion dataset
# with the project's own CLI. Usage:
#
#   bash resources/models/train_models.sh [STEP...]
#
# STEP: ae, a style name (elderly exhausted angry proud youthful feminine masculine sad happy), eval,
# pack, or nothing for all of them in that order. Environment:
#   DATA  the dataset root holding dataset-1/ and dataset-2/ (default: ../shared/data/bandai)
#   CLI   motionstyle-cli (default: build/release/app/cli/motionstyle-cli)
#   WORK  where full-precision networks, checkpoints and logs go (default: build/models)
#   OUT   where the shipped (half-precision) files go (default: resources/models)
# Every command is deterministic for its seed and thread count (--threads 2 here), so the same
# commands on the same data rebuild bit-identical files. Times per step land in $WORK/times.txt.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
DATA="${DATA:-$root/../shared/data/bandai}"
CLI="${CLI:-$root/build/release/app/cli/motionstyle-cli}"
WORK="${WORK:-$root/build/models}"
OUT="${OUT:-$here}"
D1="$DATA/dataset-1/data"
D2="$DATA/dataset-2/data"
THREADS=2
AE_EPOCHS=100
STYLE_EPOCHS=100

[[ -d "$D1" && -d "$D2" ]] || { echo "error: the Bandai dataset is not at $DATA (set DATA)" >&2; exit 2; }
[[ -x "$CLI" ]] || { echo "error: $CLI not found: build first, or set CLI" >&2; exit 2; }
mkdir -p "$WORK/content-normal"

timed() {  # timed NAME COMMAND...: runs, logs to $WORK/NAME.log, appends the wall time to times.txt
  local name=$1 start; shift
  start=$(date +%s)
  "$@" > "$WORK/$name.log" 2>&1 || { echo "error: $name failed; see $WORK/$name.log" >&2; tail -5 "$WORK/$name.log" >&2; exit 1; }
  echo "$name $(( $(date +%s) - start )) s" | tee -a "$WORK/times.txt"
}

# The normal-style dataset-2 clips are the content of every style network (walks, runs, turns).
for f in "$D2"/dataset-2_*_normal_*.bvh; do ln -sf "$f" "$WORK/content-normal/"; done

# Style clips: dataset-2 has walk, run and both turns for its styles; dataset-1 has one walk and one
# run per style, and its walk stands for the turns too.
style_args() {
  local s=$1
  case $s in
    elderly|exhausted|youthful|feminine|masculine|active)
      echo --style "walk=$D2/dataset-2_walk_${s}_001.bvh" --style "run=$D2/dataset-2_run_${s}_001.bvh" \
           --style "walk-turn-left=$D2/dataset-2_walk-turn-left_${s}_001.bvh" \
           --style "walk-turn-right=$D2/dataset-2_walk-turn-right_${s}_001.bvh" ;;
    angry|proud|sad|happy)
      echo --style "$D1/dataset-1_walk_${s}_001.bvh" --style "run=$D1/dataset-1_run_${s}_001.bvh" ;;
    *) echo "error: unknown style $s" >&2; exit 2 ;;
  esac
}

train_ae() {
  # Every clip of both parts (locomotion plus bows, waves, dashes, punches, dances...), every 10th
  # held out for evaluation.
  timed ae "$CLI" train-ae --data "$D1" "$D2" --out "$WORK/autoencoder.net" --epochs $AE_EPOCHS \
    --seed 1 --threads $THREADS --holdout 10
}

train_style() {
  local s=$1
  # shellcheck disable=SC2046
  timed "$s" "$CLI" train-style --ae "$WORK/autoencoder.net" --content "$WORK/content-normal" \
    $(style_args "$s") --out "$WORK/$s.net" --epochs $STYLE_EPOCHS --seed 1 --threads $THREADS --holdout 5
}

# The shipped files: weights in IEEE half precision (motionstyle-cli pack), which halves their size
# and changes the stylized output by far less than a millimetre (see README.md).
pack() {
  local name
  for name in autoencoder $ALL_STYLES; do
    [[ -f "$WORK/$name.net" ]] || continue
    "$CLI" pack "$WORK/$name.net" --out "$OUT/$name.net" --precision f16
  done
}

# Evaluation of the SHIPPED files: the clips each training held back (listed at the end of its log),
# plus the two redistributable samples (another skeleton, another studio), raw (eval) and after the
# IK clean-up (stylize --metrics).
evaluate() {
  local s held sample walk_style
  for s in $ALL_STYLES; do
    [[ -f "$OUT/$s.net" ]] || continue
    mapfile -t held < <(sed -n 's/^held out: //p' "$WORK/$s.log")
    # shellcheck disable=SC2046
    timed "$s.eval" "$CLI" eval --ae "$OUT/autoencoder.net" --net "$OUT/$s.net" $(style_args "$s") \
      --json "$WORK/$s.eval.json" "${held[@]}"
    walk_style=$(style_args "$s" | tr ' ' '\n' | grep -m1 '_walk_' | sed 's/^walk=//')
    timed "$s.eval-samples" "$CLI" eval --ae "$OUT/autoencoder.net" --net "$OUT/$s.net" --style "$walk_style" \
      --json "$WORK/$s.samples.eval.json" "$root/resources/samples/cmu_131_01_walk.bvh" "$root/resources/samples/zombie_walk.bvh"
    for sample in cmu_131_01_walk zombie_walk; do
      timed "$s.$sample" "$CLI" stylize --net "$OUT/$s.net" "$root/resources/samples/$sample.bvh" \
        --out "$WORK/$s.$sample.bvh" --metrics "$WORK/$s.$sample.metrics.json"
    done
    timed "$s.heldout-cleanup" "$CLI" stylize --net "$OUT/$s.net" "${held[0]}" \
      --out "$WORK/$s.heldout.bvh" --metrics "$WORK/$s.heldout.metrics.json"
  done
}

ALL_STYLES="elderly exhausted angry proud youthful feminine masculine sad happy"
steps=("$@")
[[ ${#steps[@]} -gt 0 ]] || steps=(ae $ALL_STYLES pack eval)
for step in "${steps[@]}"; do
  case $step in
    ae) train_ae ;;
    pack) pack ;;
    eval) evaluate ;;
    *) train_style "$step" ;;
  esac
done
