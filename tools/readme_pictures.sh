#!/usr/bin/env bash
# Regenerates the pictures of README.md and the user guide (docs/*.png) from the tools
# themselves, so that none shows an older run. Run from the repository root after
# `cargo build --release`; needs rsvg-convert (librsvg2-bin) and, for the viewer picture,
# headless Chromium. The tolerance trade-off (docs/square-tradeoff.png) takes minutes and
# is made only with --all.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=target/release
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# README: a 17-tile serpentine's final shape
"$bin/fold-run" "S*4 L L S*4 R R S*4" --quiet --frames 2 --out "$tmp/serpentine" >/dev/null
rsvg-convert -w 900 -b white "$tmp/serpentine/final.svg" -o docs/fold-run-serpentine.png

# docs/planner.md: the key's plan preview
"$bin/fold-plan" shapes/key.svg --tiles 171 --quiet --preview "$tmp/key.svg" >/dev/null
rsvg-convert -w 900 -b white "$tmp/key.svg" -o docs/plan-key-171.png

# docs/designing.md: the viewer at the end of the key's run, in its own default view (the
# camera following the fold ends framed on the folded key); the time budget lets the page
# finish drawing
"$bin/fold-run" shapes/key.svg --tiles 171 --quiet --frames 2 --out "$tmp/key" >/dev/null
chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1000,700 \
  --force-device-scale-factor=1 --virtual-time-budget=3000 --user-data-dir="$tmp/profile" \
  --screenshot="$tmp/viewer.png" "file://$tmp/key/index.html#t=end" 2>/dev/null
cp "$tmp/viewer.png" docs/viewer-key.png

if [ "${1:-}" = "--all" ]; then
  "$bin/fold-tolerance" shapes/square.svg --tiles 107 --turns tight --optimize --target 0.99 \
    --search-samples 200 --samples 10000 --quiet --plot "$tmp/square-tradeoff.svg" >/dev/null
  rsvg-convert -w 900 -b white "$tmp/square-tradeoff.svg" -o docs/square-tradeoff.png
fi
echo "docs/*.png regenerated"
