#!/usr/bin/env bash
# A new user's first hour, automated: a fresh crate that depends on rootclip
# with the README's Cargo.toml line (as a path) and `default-features = false`,
# and the README's .cargo/config.toml snippet; the README's Rust examples are
# its binaries, built and run as written. Fails if clap, indicatif or
# serde_json end up in the dependency tree.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
crate="$work/fresh"
mkdir -p "$crate/src/bin" "$crate/.cargo"
cat > "$crate/Cargo.toml" <<TOML
[package]
name = "fresh"
version = "0.0.0"
edition = "2021"
publish = false

[dependencies]
rootclip = { path = "$root", default-features = false }

[workspace]
TOML
echo 'fn main() {}' > "$crate/src/main.rs"
# The README's fenced blocks: the .cargo/config.toml snippet and the Rust examples.
python3 - "$root/README.md" "$crate" <<'PY'
import re, sys
readme, crate = open(sys.argv[1]).read(), sys.argv[2]
blocks = re.findall(r"```(\w+)\n(.*?)```", readme, re.S)
config = [b for lang, b in blocks if lang == "toml" and b.startswith("# .cargo/config.toml")]
assert len(config) == 1, "README: exactly one .cargo/config.toml block"
open(f"{crate}/.cargo/config.toml", "w").write(config[0])
rust = [b for lang, b in blocks if lang == "rust"]
assert rust, "README: no Rust examples"
for k, b in enumerate(rust):
    open(f"{crate}/src/bin/readme_{k}.rs", "w").write(b)
print(f"{len(rust)} README examples")
PY
cp "$root/Cargo.lock" "$crate/Cargo.lock"
cd "$crate"
unset RUSTFLAGS CARGO_ENCODED_RUSTFLAGS || true
export CARGO_TARGET_DIR="$root/target/fresh-crate"
if cargo tree -e normal --prefix none | grep -E '^(clap|indicatif|serde_json) '; then
    echo "fresh-crate-check: the library pulls in CLI dependencies" >&2
    exit 1
fi
cargo build --bins --quiet
for bin in src/bin/readme_*.rs; do
    name=$(basename "$bin" .rs)
    echo "== $name"
    "$CARGO_TARGET_DIR/debug/$name" > /dev/null
done
echo "fresh-crate-check: ok"
