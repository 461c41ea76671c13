#!/usr/bin/env bash
# Coverage-guided fuzzing (libFuzzer through cargo-fuzz) of the entry points that
# read user input: the scene loader (TOML and --set), the OBJ/MTL path, the PFM
# reader and the image loaders. Each target runs a fixed number of executions
# (default 1,000,000; `tools/fuzz.sh 20000` for a quick pass; name targets after the
# count to run only those). Seeds are the catalogue's own files. A crash leaves its
# input in fuzz/artifacts/TARGET/ and stops the script with a non-zero status.
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-1000000}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene obj_mtl pfm images)

rustup run nightly rustc --version >/dev/null 2>&1 || rustup toolchain install nightly --profile minimal
cargo fuzz --version >/dev/null 2>&1 || cargo install cargo-fuzz

# Seed corpora, made afresh from the repository.
seeds=fuzz/seeds
rm -rf "$seeds"
mkdir -p "$seeds"/{scene,obj_mtl,pfm,images}
cp algorithms/*.toml "$seeds/scene/"
for obj in algorithms/models/*.obj; do
  mtl="${obj%.obj}.mtl"
  { cat "$obj"; printf '\0'; [ -f "$mtl" ] && cat "$mtl"; } >"$seeds/obj_mtl/$(basename "$obj")"
done
printf 'PF\n2 1\n-1.0\n' >"$seeds/pfm/colour"
head -c 24 /dev/zero >>"$seeds/pfm/colour"
printf 'Pf\n1 2\n1.0\n' >"$seeds/pfm/grey"
head -c 8 /dev/zero >>"$seeds/pfm/grey"
cp algorithms/textures/*.png "$seeds/images/"
ls -S golden/*.png | tail -n 4 | xargs -I{} cp {} "$seeds/images/"
ls -S golden/*.exr | tail -n 2 | xargs -I{} cp {} "$seeds/images/"

for target in "${targets[@]}"; do
  mkdir -p "fuzz/corpus/$target" "fuzz/artifacts/$target"
  echo "== $target: $runs executions"
  start=$(date +%s)
  log="fuzz/artifacts/$target/last-run.log"
  status=0
  cargo +nightly fuzz run --fuzz-dir fuzz "$target" "fuzz/corpus/$target" "$seeds/$target" -- \
    -runs="$runs" -max_len=65536 -rss_limit_mb=4096 -timeout=20 -print_final_stats=1 \
    -artifact_prefix="fuzz/artifacts/$target/" >"$log" 2>&1 || status=$?
  grep -E '^(stat::number_of_executed_units|stat::peak_rss_mb|Done [0-9]+ runs|==[0-9]+== ?ERROR|SUMMARY|thread .* panicked)' "$log" || true
  if [ "$status" -ne 0 ]; then
    echo "   $target failed (status $status): see $log and fuzz/artifacts/$target/"
    exit "$status"
  fi
  echo "   $(( $(date +%s) - start )) s"
done
