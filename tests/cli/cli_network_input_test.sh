#!/usr/bin/env bash
# Hostile network files at the CLI (issue 13): CRC-valid files with non-physical statistics or unsafe
# metadata strings, and network files with hostile names. Each must give exit code 2 (bad input, the
# message naming the file) or a clean listing, never exit 1 ("internal error"), never a raw control
# character on the terminal, and JSON output must stay valid.
# Usage: cli_network_input_test.sh <motionstyle-cli> <tests/data>
set -u
source "$(dirname "${BASH_SOURCE[0]}")/cli_test_lib.sh"  # cli, data, work, failures, expect, fail

no_control_characters() {  # after expect: neither output holds ESC, BEL or another C0 control but tab/newline
  if LC_ALL=C grep -q $'[\x01-\x08\x0b-\x1f\x7f]' "$work/out" "$work/err"; then
    echo "FAIL: raw control characters in the output of the previous command"; failures=$((failures + 1))
  fi
}

valid_utf8_output() {  # after expect: stdout is valid UTF-8 (JSON must be)
  if ! iconv -f UTF-8 -t UTF-8 "$work/out" >/dev/null 2>&1; then
    echo "FAIL: the output of the previous command is not valid UTF-8"; failures=$((failures + 1))
  fi
}

# Byte surgery on a network file (NETWORK_FORMAT.md): overwrite bytes, then restore the trailing CRC-32
# (gzip's trailer holds the same zlib CRC-32 of its input, little-endian, in its first 4 bytes).
put_bytes() {  # put_bytes <file> <offset> <printf-escaped bytes>
  printf "$3" | dd of="$1" bs=1 seek="$2" conv=notrunc status=none
}
fix_crc() {
  local size
  size=$(stat -c %s "$1")
  head -c $((size - 4)) "$1" | gzip -c | tail -c 8 | head -c 4 | dd of="$1" bs=1 seek=$((size - 4)) conv=notrunc status=none
}
u32_at() { od -An -tu4 -j "$2" -N4 "$1" | tr -d ' '; }

# A valid loss network, trained here in a second.
expect 0 "wrote" "$cli" train-loss-network --data "$data/zombie.bvh" --out "$work/ae.net" --epochs 1 --hidden 8 --threads 1
joint_set_length=$(u32_at "$work/ae.net" 32)
mean=$((24 + 8 + 4 + joint_set_length + 8 + 4 + 4))  # header, fps, joint set, height, feature count, count
std=$((mean + 66 * 8 + 4))

# 1. Non-physical statistics: exit 2 naming the file and the field (was exit 1, "internal error").
crafted() {  # crafted <name> <offset> <f64 bytes, printf-escaped>
  cp "$work/ae.net" "$work/$1.net"
  put_bytes "$work/$1.net" "$2" "$3"
  fix_crc "$work/$1.net"
}
crafted huge_mean "$mean" '\xa0\xc8\xeb\x85\xf3\xcc\xe1\x7f'            # +1e308
crafted negative_huge_mean $((mean + 8 * 65)) '\xa0\xc8\xeb\x85\xf3\xcc\xe1\xff'  # -1e308
crafted tiny_std "$std" '\xe1\xf5\x93\x35\xe6\x24\x71\x01'              # 1e-301
crafted denormal_std $((std + 8 * 64)) '\x01\x00\x00\x00\x00\x00\x00\x00'  # 5e-324
for name in huge_mean negative_huge_mean; do
  expect 2 "$name.net: .*normalisation mean" "$cli" info "$work/$name.net"
  expect 2 "$name.net: .*normalisation mean" "$cli" info "$data/zombie.bvh" --loss-network "$work/$name.net"
done
for name in tiny_std denormal_std; do
  expect 2 "$name.net: .*normalisation std" "$cli" info --json "$work/$name.net"
  expect 2 "$name.net: .*normalisation std" "$cli" info "$data/cmu_131_01.bvh" --loss-network "$work/$name.net"
done

# The finding itself: stylizing with such a style network was exit 1 ("contacts: positions hold a
# non-finite value").
expect 0 "wrote" "$cli" train-style --loss-network "$work/ae.net" --content "$data/zombie.bvh" --style "$data/cmu_131_01.bvh" \
  --out "$work/style.net" --epochs 1 --hidden 1 --threads 1
cp "$work/style.net" "$work/huge_mean_style.net"
put_bytes "$work/huge_mean_style.net" "$mean" '\xa0\xc8\xeb\x85\xf3\xcc\xe1\x7f'
fix_crc "$work/huge_mean_style.net"
expect 2 "huge_mean_style.net: .*normalisation mean\[0\]" "$cli" stylize --net "$work/huge_mean_style.net" \
  "$data/zombie.bvh" --out "$work/styled.bvh"

# 2. Unsafe metadata strings: refused on load (exit 2), and nothing raw reaches the terminal.
tool_value="motionstyle core/style training"  # a property value train-loss-network writes (31 bytes)
tool_at=$(LC_ALL=C grep -obUa "$tool_value" "$work/ae.net" | head -n 1 | cut -d: -f1)
cp "$work/ae.net" "$work/escape.net"
put_bytes "$work/escape.net" "$tool_at" '\x1b]0;title\x07xxxxxxxxxxxxxxxxxxxx'
fix_crc "$work/escape.net"
cp "$work/ae.net" "$work/invalid_utf8.net"
put_bytes "$work/invalid_utf8.net" "$tool_at" '\xff\xfe\xc3(xxxxxxxxxxxxxxxxxxxxxxxxxxx'
fix_crc "$work/invalid_utf8.net"
expect 2 "escape.net: .*control character 0x1b" "$cli" info "$work/escape.net"
no_control_characters
expect 2 "escape.net: .*control character" "$cli" info --json "$work/escape.net"
no_control_characters
expect 2 "invalid_utf8.net: .*invalid UTF-8" "$cli" info --json "$work/invalid_utf8.net"
expect 2 "invalid_utf8.net: .*invalid UTF-8" "$cli" info "$data/zombie.bvh" --loss-network "$work/invalid_utf8.net"

# models: the broken files are listed as unreadable (exit 2), the JSON stays valid, nothing raw leaks.
mkdir -p "$work/res/models" "$work/res/samples"
cp "$work/escape.net" "$work/invalid_utf8.net" "$work/huge_mean.net" "$work/res/models/"
cp "$work/ae.net" "$work/res/models/loss_network.net"
expect 2 "escape.*UNREADABLE.*control character" env MOTIONSTYLE_RESOURCES="$work/res" "$cli" models
no_control_characters
expect 2 '"error"' env MOTIONSTYLE_RESOURCES="$work/res" "$cli" models --json
no_control_characters
valid_utf8_output

# 3. Hostile file and folder names (escaped on output anyway; shipped network names are plain ASCII
# already, so the resources folder carries them): a good network and a broken one under folders whose
# names hold an escape sequence or invalid UTF-8 list and describe cleanly.
evil="$work/evil"$'\x1b]0;title\x07'
latin1="$work/caf"$'\xe9'
for folder in "$evil" "$latin1"; do
  mkdir -p "$folder/models" "$folder/samples"
  cp "$work/ae.net" "$folder/models/loss_network.net"
  printf 'junk' >"$folder/models/broken.net"
done
expect 2 "loss_network  *loss_network" env MOTIONSTYLE_RESOURCES="$evil" "$cli" models
no_control_characters
expect 2 '"networks"' env MOTIONSTYLE_RESOURCES="$latin1" "$cli" models --json
no_control_characters
valid_utf8_output
expect 2 "broken.net" env MOTIONSTYLE_RESOURCES="$evil" "$cli" info broken
no_control_characters
expect 0 "loss network" "$cli" info "$evil/models/loss_network.net"
no_control_characters
expect 0 '"network"' "$cli" info --json "$latin1/models/loss_network.net"
valid_utf8_output

# The valid file itself is untouched by all this.
expect 0 "loss network" "$cli" info "$work/ae.net"

if [ "$failures" -ne 0 ]; then echo "$failures network-input check(s) failed"; exit 1; fi
echo "all network-input checks passed"
