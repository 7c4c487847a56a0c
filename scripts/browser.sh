#!/usr/bin/env bash
# The lab in a real browser (issue 26): builds the page (web/build.sh), serves it on 127.0.0.1,
# loads it in headless Chromium (web/check.mjs), runs every panel's check and compares the
# fingerprints with the native build's bit for bit; writes each panel's screenshot and the
# costs to target/lab/. A page error or a mismatch fails. `--docs` also copies the screenshots
# to docs/img/lab/ for the guide. Installs Debian's chromium and the npm package
# playwright-core (web/package-lock.json) when they are missing.
set -euo pipefail
cd "$(dirname "$0")/.."
out=target/lab
mkdir -p "$out"
if ! [ -x /usr/bin/chromium ]; then
  echo "browser: installing Debian's chromium"
  apt-get install -y -q chromium > /dev/null || { apt-get update -q > /dev/null && apt-get install -y -q chromium > /dev/null; }
fi
(cd web && npm ci --no-audit --no-fund --silent)
bash web/build.sh
cargo run -q -p odyn-web --features deterministic > "$out/native.txt"
# The server: a free port chosen by Python, on the loopback interface only.
python3 -u -m http.server 0 --bind 127.0.0.1 --directory web > "$out/server.log" 2>&1 &
server=$!
trap 'kill $server 2> /dev/null' EXIT
for _ in $(seq 50); do
  port=$(sed -n 's/.*port \([0-9]*\).*/\1/p' "$out/server.log" | head -1)
  [ -n "$port" ] && break
  sleep 0.1
done
if [ -z "${port:-}" ]; then
  echo "browser: the page server did not start" >&2
  cat "$out/server.log" >&2
  exit 1
fi
node web/check.mjs "http://127.0.0.1:$port/index.html" "$out" > "$out/browser.txt"
if diff "$out/native.txt" "$out/browser.txt"; then
  echo "browser: $(wc -l < "$out/native.txt") panels bit-identical with native; screenshots in $out/"
else
  echo "browser: native (<) and browser (>) fingerprints differ" >&2
  exit 1
fi
if [ "${1:-}" = "--docs" ]; then
  mkdir -p docs/img/lab
  cp "$out"/{spring,pendulum,cloth,gray_scott,dam_break,mpm}.png docs/img/lab/
fi
