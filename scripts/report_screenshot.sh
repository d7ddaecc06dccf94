#!/usr/bin/env bash
# Renders a workspace's HTML report (colmap gcn_report) to a PNG with
# Debian's headless Chromium, as the README's picture was made:
#   bash scripts/report_screenshot.sh demo/workspace docs/figures/demo_report.png
set -euo pipefail
workspace=${1:?usage: report_screenshot.sh WORKSPACE OUT.png [WIDTHxHEIGHT]}
out=${2:?usage: report_screenshot.sh WORKSPACE OUT.png [WIDTHxHEIGHT]}
size=${3:-1200,2400}
cd "$(dirname "$0")/.."
export PATH="$PWD/build/bin:$PATH"
report=$(colmap gcn_report --workspace_path "$workspace" | tail -n 1)
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
chromium --headless --no-sandbox --disable-gpu --hide-scrollbars \
  --user-data-dir="$profile" --window-size="${size/x/,}" \
  --screenshot="$(realpath -m "$out")" "file://$(realpath "$report")" \
  2>/dev/null
echo "$out"
