#!/usr/bin/env bash
# Builds the static viewer: the library compiled to WebAssembly (web/, the engine the
# page's Web Worker runs), its JavaScript glue, and the page (web/page/), into
# target/web/viewer/ (or $LUMIERE_WEB_OUT). Installs what is missing first: Debian's
# rustc-web, which builds the wasm32 standard library from source, and
# wasm-bindgen-cli at exactly the version of web/Cargo.lock. Prints the output
# folder. Safe to call from several tests at once.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="${LUMIERE_WEB_OUT:-$root/target/web/viewer}"
mkdir -p "$out" "$root/target/web"
out="$(cd "$out" && pwd)"
tools="$root/target/web/tools"
bindgen="$tools/bin/wasm-bindgen"
version="$(awk '$0 == "name = \"wasm-bindgen\"" { getline; gsub(/^version = "|"$/, ""); print }' \
    "$root/web/Cargo.lock")"

# The tools, inside the install lock (a caller that waited finds them there).
(
    . "$root/tools/install-lock.sh"
    # lld-22: rust-web-llvm's rust-lld (the wasm linker) points to it.
    "$root/tools/apt-install.sh" rustc-web cargo-web rust-web-src rust-web-llvm lld-22
    if [ "$("$bindgen" --version 2>/dev/null)" != "wasm-bindgen $version" ]; then
        # The rustup toolchain (first on PATH) builds it, into a folder of the project:
        # with the versions of its own lock file, or, when the registry has lost one of
        # them, with the newest that fit.
        install=(env -u CARGO_TARGET_DIR -u RUSTC -u RUSTFLAGS -u CARGO_ENCODED_RUSTFLAGS
            cargo install --force wasm-bindgen-cli --version "=$version" --root "$tools")
        if ! "${install[@]}" --locked >&2; then
            echo "build-web.sh: wasm-bindgen-cli's lock file does not resolve;" \
                "installing it without --locked" >&2
            "${install[@]}" >&2
        fi
    fi
)

# One build at a time: the second caller finds the build done and the output the same.
exec 8>"$root/target/web/build.lock"
flock 8

# Debian's compiler by full path (rustup's comes first on PATH), in a target folder of
# its own: the two compilers' artefacts do not mix. No flags: getrandom takes its
# wasm_js backend from the feature alone (Cargo.toml), and +simd128 was no faster
# (the shadow volumes 10% slower). A change to the library's dependencies updates
# web/Cargo.lock here.
cd "$root/web"
env -u RUSTC_WRAPPER -u CARGO_BUILD_RUSTFLAGS -u CARGO_ENCODED_RUSTFLAGS \
    RUSTC=/usr/bin/rustc RUSTDOC=/usr/bin/rustdoc RUSTC_BOOTSTRAP=1 \
    CARGO_TARGET_DIR="$root/target/web/cargo" RUSTFLAGS="" \
    /usr/bin/cargo build --release \
    -Zbuild-std=std,panic_abort --target wasm32-unknown-unknown >&2
wasm="$root/target/web/cargo/wasm32-unknown-unknown/release/lumiere_web.wasm"

# The folder is made beside the output and swapped in only when it differs, so that a
# page served from the output while another caller builds keeps its files.
stage="$(mktemp -d "$out.XXXXXX")"
trap 'rm -rf "$stage" "$out.old"' EXIT
"$bindgen" --target web --out-dir "$stage/pkg" "$wasm"
if [ -d "$root/web/page" ]; then
    cp -R "$root/web/page/." "$stage/"
fi
chmod 755 "$stage"
if ! diff -r -q "$stage" "$out" >/dev/null 2>&1; then
    rm -rf "$out.old"
    mv "$out" "$out.old"
    mv "$stage" "$out"
fi
echo "$out"
