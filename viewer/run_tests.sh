#!/usr/bin/env bash
# The viewer's and the glTF export's tests outside Rust:
#  - the viewer page in a real headless browser (Debian's Chromium driven by playwright-core):
#    it loads with no console errors and no network, shows the bodies, and scrubbing changes it;
#  - the exported .glb files pass the Khronos glTF validator (npm gltf-validator).
# Installs what it needs: Chromium with apt-get (as root) when missing, the npm packages with npm ci.
# With --screenshots it also writes the README's pictures to docs/images/.
set -euo pipefail
cd "$(dirname "$0")"
root=$(cd .. && pwd)

if [ ! -x /usr/bin/chromium ]; then
    echo "== installing chromium (Debian package) =="
    if [ "$(id -u)" -ne 0 ]; then
        echo "error: /usr/bin/chromium is missing; install it with: sudo apt-get install chromium" >&2
        exit 1
    fi
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
fi

if [ ! -f node_modules/.package-lock.json ] || [ package-lock.json -nt node_modules/.package-lock.json ]; then
    echo "== npm ci (viewer) =="
    npm ci --no-audit --no-fund
fi

# The test profile is what `cargo test` already built, so this reuses its work.
echo "== building tumble =="
cargo build --profile test --locked -p tumble-cli --bin tumble --manifest-path "$root/Cargo.toml"
tumble="$root/target/debug/tumble"

out=test-output
rm -rf "$out"
mkdir -p "$out"
"$tumble" view "$root/scenes/demo.toml" -o "$out/demo.html"
"$tumble" view "$root/scenes/shapes.toml" -o "$out/shapes.html"
"$tumble" run "$root/scenes/projectile.toml" --out "$out/projectile.csv" >/dev/null
"$tumble" view "$out/projectile.csv" --scene "$root/scenes/projectile.toml" -o "$out/projectile.html"
"$tumble" export "$root/scenes/demo.toml" -o "$out/demo.glb"
"$tumble" export "$root/scenes/shapes.toml" -o "$out/shapes.glb"
"$tumble" export "$out/projectile.csv" --scene "$root/scenes/projectile.toml" -o "$out/projectile.glb"

export TUMBLE_VIEWER_PAGES="$out/demo.html,$out/shapes.html,$out/projectile.html"
export TUMBLE_GLB_FILES="$out/demo.glb,$out/shapes.glb,$out/projectile.glb"
if [ "${1:-}" = --screenshots ]; then
    mkdir -p "$root/docs/images"
    export TUMBLE_SCREENSHOTS="demo.html=$root/docs/images/viewer.png,shapes.html=$root/docs/images/viewer-shapes.png"
    export TUMBLE_SCREENSHOT_TIME=2.4
    "$tumble" run "$root/scenes/demo.toml" --out "$out/demo.csv" >/dev/null
    "$tumble" plot "$out/demo.csv" -o "$root/docs/images/omega.png" --what omega_body:handle,omega:handle
fi
echo "== node --test (viewer/tests) =="
node --test tests/
