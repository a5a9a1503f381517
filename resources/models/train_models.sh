#!/usr/bin/env bash
# Rebuilds every shipped network in resources/models/ from the Bandai Namco Research motion dataset
# with the project's own CLI. Usage:
#
#   bash resources/models/train_models.sh [STEP...]
#
# STEP: loss_network (formerly ae), a style name (elderly exhausted angry proud youthful feminine masculine sad happy), pack,
# memory, eval, or nothing for all of them in that order. Environment:
#   DATA  the dataset root holding dataset-1/ and dataset-2/ (default: ../shared/data/bandai)
#   CLI   motionstyle-cli (default: build/release/app/cli/motionstyle-cli)
#   EVAL  eval_generalisation (default: build/release/tests/bench/quality/eval_generalisation)
#   WORK  where full-precision networks, checkpoints and logs go (default: build/models)
#   OUT   where the shipped (half-precision) files go (default: resources/models)
# Every command is deterministic for its seed and thread count (--threads 2 here), so the same
# commands on the same data rebuild bit-identical files. Times per step land in $WORK/times.txt.
# Everything not given below is the CLI's default (motionstyle-cli train-loss-network --help, train-style --help).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
DATA="${DATA:-$root/../shared/data/bandai}"
CLI="${CLI:-$root/build/release/app/cli/motionstyle-cli}"
EVAL="${EVAL:-$root/build/release/tests/bench/quality/eval_generalisation}"
WORK="${WORK:-$root/build/models}"
OUT="${OUT:-$here}"
D1="$DATA/dataset-1/data"
D2="$DATA/dataset-2/data"
THREADS=2
LOSS_NETWORK_EPOCHS=40
STYLE_EPOCHS=100

[[ -d "$D1" && -d "$D2" ]] || { echo "error: the Bandai dataset is not at $DATA (set DATA)" >&2; exit 2; }
[[ -x "$CLI" ]] || { echo "error: $CLI not found: build first, or set CLI" >&2; exit 2; }
mkdir -p "$WORK/content"

timed() {  # timed NAME COMMAND...: runs, logs to $WORK/NAME.log, appends the wall time to times.txt
  local name=$1 start; shift
  start=$(date +%s)
  "$@" > "$WORK/$name.log" 2>&1 || { echo "error: $name failed; see $WORK/$name.log" >&2; tail -5 "$WORK/$name.log" >&2; exit 1; }
  echo "$name $(( $(date +%s) - start )) s" | tee -a "$WORK/times.txt"
}

# The content of every style network: the normal-style locomotion clips of dataset-2 (walks, runs,
# turns); train-style --holdout 5 keeps every 5th (sorted) out for the evaluation (eval_generalisation's
# Bandai set). All 755 locomotion clips of every style measured worse (docs/decisions.md).
rm -f "$WORK"/content/*.bvh
for f in $(ls "$D2"/*.bvh | grep -E "dataset-2_(walk|run|walk-turn-left|walk-turn-right)_normal_"); do
  ln -s "$f" "$WORK/content/"
done

# Style clips: dataset-2 has walk, run and both turns for its styles; dataset-1 one walk and one run per
# style. The walk is also the default for content labels without their own clip.
style_args() {
  local s=$1
  case $s in
    elderly|exhausted|youthful|feminine|masculine|active)
      echo --style "$D2/dataset-2_walk_${s}_001.bvh" --style "run=$D2/dataset-2_run_${s}_001.bvh" \
           --style "walk-turn-left=$D2/dataset-2_walk-turn-left_${s}_001.bvh" \
           --style "walk-turn-right=$D2/dataset-2_walk-turn-right_${s}_001.bvh" ;;
    angry|proud|sad|happy)
      echo --style "$D1/dataset-1_walk_${s}_001.bvh" --style "run=$D1/dataset-1_run_${s}_001.bvh" ;;
    *) echo "error: unknown style $s" >&2; exit 2 ;;
  esac
}

train_loss_network() {
  # Every clip of both parts (locomotion, hand raising and waving, bows, punches, dances...), every
  # 10th held out for evaluation; the defaults augment the rigs (girdle 75, offsets 20, mirroring).
  timed loss_network "$CLI" train-loss-network --data "$D1" "$D2" --out "$WORK/loss_network.net" --epochs $LOSS_NETWORK_EPOCHS \
    --seed 1 --threads $THREADS --holdout 10
}

train_style() {
  local s=$1
  # shellcheck disable=SC2046
  timed "$s" "$CLI" train-style --loss-network "$WORK/loss_network.net" --content "$WORK/content" \
    $(style_args "$s") --out "$WORK/$s.net" --epochs $STYLE_EPOCHS --seed 1 --threads $THREADS --holdout 5
}

# The shipped files: weights in IEEE half precision (motionstyle-cli pack), which halves their size
# and changes the stylized output by far less than a millimetre (see README.md).
pack() {
  local name
  for name in loss_network $ALL_STYLES; do
    [[ -f "$WORK/$name.net" ]] || continue
    "$CLI" pack "$WORK/$name.net" --out "$OUT/$name.net" --precision f16
  done
}

# Evaluation of the SHIPPED files on the held-out Bandai clips and the other studios' clips
# (eval_generalisation: reconstruction, familiarity, style and content distances, clean-up, path),
# with the path kept (the default) and at free pace.
evaluate() {
  [[ -x "$EVAL" ]] || { echo "error: $EVAL not found: build first, or set EVAL" >&2; exit 2; }
  timed eval "$EVAL" --models "$OUT" --data "$DATA" --json "$WORK/eval.json"
  # The same at free pace (the style may change the path), without the clean-up: the README's
  # figures in brackets.
  timed eval-free-pace "$EVAL" --models "$OUT" --data "$DATA" --path style --no-cleanup --json "$WORK/eval_free.json"
  cat "$WORK/eval.log"
}

# The shipped loss network's reconstruction memory of its training clips (style/reconstruction_memory.h):
# adapt keeps what the network reconstructs of them without the clips. Made with the SHIPPED (packed)
# loss network, whose encoder it must match, over the same split as train_loss_network.
remember() {
  timed memory "$CLI" remember --loss-network "$OUT/loss_network.net" --data "$D1" "$D2" --holdout 10 --threads $THREADS \
    --description "the Bandai Namco Research motion datasets 1 and 2, training split (CC BY-NC 4.0)" \
    --out "$OUT/loss_network.memory"
}

ALL_STYLES="elderly exhausted angry proud youthful feminine masculine sad happy"
steps=("$@")
[[ ${#steps[@]} -gt 0 ]] || steps=(loss_network $ALL_STYLES pack memory eval)
for step in "${steps[@]}"; do
  case $step in
    loss_network | ae) train_loss_network ;;  # ae: its former name
    pack) pack ;;
    memory) remember ;;
    eval) evaluate ;;
    *) train_style "$step" ;;
  esac
done
