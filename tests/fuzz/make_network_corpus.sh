#!/usr/bin/env bash
# Regenerates the network fuzz target's seed corpus (corpus/network/) with motionstyle-cli: tiny valid
# networks (one hidden unit, one epoch, so each seed stays a few KB) in f32 and f16, and broken copies
# that each break one rule of core/nn/NETWORK_FORMAT.md. Usage: make_network_corpus.sh <motionstyle-cli>
set -euo pipefail
cli="$1"
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
data="$root/tests/data"
out="$root/tests/fuzz/corpus/network"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
rm -f "$out"/*

tiny=(--epochs 1 --hidden 1 --threads 1)
"$cli" train-loss-network --data "$data/zombie.bvh" --out "$out/valid_ae_f32.net" "${tiny[@]}" >/dev/null
"$cli" train-style --loss-network "$out/valid_ae_f32.net" --content "$data/zombie.bvh" --style "$data/cmu_131_01.bvh" \
  --out "$out/valid_style_f32.net" "${tiny[@]}" >/dev/null
"$cli" pack "$out/valid_ae_f32.net" --out "$out/valid_ae_f16.net" --precision f16 >/dev/null
"$cli" pack "$out/valid_style_f32.net" --out "$out/valid_style_f16.net" --precision f16 >/dev/null

put_bytes() { printf "$3" | dd of="$1" bs=1 seek="$2" conv=notrunc status=none; }
fix_crc() {  # gzip's trailer starts with the zlib CRC-32 of its input, little-endian
  local size
  size=$(stat -c %s "$1")
  head -c $((size - 4)) "$1" | gzip -c | tail -c 8 | head -c 4 | dd of="$1" bs=1 seek=$((size - 4)) conv=notrunc status=none
}
ae="$out/valid_ae_f16.net"
size=$(stat -c %s "$ae")
head -c $((size / 2)) "$ae" >"$out/broken_truncated.net"
cp "$ae" "$out/broken_magic.net" && put_bytes "$out/broken_magic.net" 0 'MSTYLNEX'
cp "$ae" "$out/broken_future_version.net" && put_bytes "$out/broken_future_version.net" 8 '\x04' && fix_crc "$out/broken_future_version.net"
cp "$ae" "$out/broken_crc.net" && put_bytes "$out/broken_crc.net" 100 '\x55'
joint_set_length=$(od -An -tu4 -j 32 -N4 "$ae" | tr -d ' ')
mean=$((24 + 8 + 4 + joint_set_length + 8 + 4 + 4))
cp "$ae" "$out/broken_huge_mean.net" && put_bytes "$out/broken_huge_mean.net" "$mean" '\xa0\xc8\xeb\x85\xf3\xcc\xe1\x7f' &&
  fix_crc "$out/broken_huge_mean.net"
tool_at=$(LC_ALL=C grep -obUa "motionstyle core/style training" "$ae" | head -n 1 | cut -d: -f1)
cp "$ae" "$out/broken_escape.net" && put_bytes "$out/broken_escape.net" "$tool_at" '\x1b]0;title\x07' &&
  fix_crc "$out/broken_escape.net"
rm -f "$out"/*.checkpoint*  # training leaves its checkpoints next to the output
du -sh "$out"
