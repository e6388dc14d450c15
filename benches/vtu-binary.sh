#!/usr/bin/env bash
# Binary against ASCII VTU on the demo wing (752 k tets): one mesh run writes the same mesh
# three times in each encoding (`-o` repeated), and the CLI's own `write` timings give each
# write; prints the file sizes, the best write time of each, and the ratios.
#
#     benches/vtu-binary.sh
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
make -s -C "$ROOT" setup
cargo build --release -q --manifest-path "$ROOT/Cargo.toml"
TF=$ROOT/target/release/tetrafoil
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
best_write() { # stderr of a run -> its smallest `write` time
  grep -E '^write ' "$1" | awk '{print $2}' | sort -g | head -1
}
"$TF" mesh "$ROOT/samples/wing/case.toml" -o "$work/a1.vtu" -o "$work/a2.vtu" -o "$work/a3.vtu" 2> "$work/ascii.log"
"$TF" mesh "$ROOT/samples/wing/case.toml" --binary -o "$work/b1.vtu" -o "$work/b2.vtu" -o "$work/b3.vtu" 2> "$work/binary.log"
ascii_bytes=$(stat -c %s "$work/a1.vtu")
binary_bytes=$(stat -c %s "$work/b1.vtu")
ascii_s=$(best_write "$work/ascii.log")
binary_s=$(best_write "$work/binary.log")
tets=$(grep -o 'volume mesh: [0-9]* tets' "$work/ascii.log" | grep -o '[0-9]*')
printf '%-8s %10s %12s %8s\n' encoding tets bytes write_s
printf '%-8s %10s %12s %8s\n' ascii "$tets" "$ascii_bytes" "$ascii_s"
printf '%-8s %10s %12s %8s\n' binary "$tets" "$binary_bytes" "$binary_s"
awk -v a="$ascii_bytes" -v b="$binary_bytes" -v s="$ascii_s" -v t="$binary_s" \
  'BEGIN { printf "binary is %.2fx smaller and writes %.2fx faster\n", a / b, s / t }'
