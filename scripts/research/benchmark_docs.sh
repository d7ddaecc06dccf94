#!/usr/bin/env bash
# Refreshes the measured part of docs/benchmarks.md from a benchmark output
# folder (default benchmark-out/, written by scripts/research/benchmark_all.sh): the
# text above the "generated below" marker is kept, everything below is
# replaced by <OUT>/report.md, with figure links pointing into <OUT>.
set -euo pipefail
source "$(dirname "$0")/common.sh"
OUT="${1:-benchmark-out}"
DOC=docs/benchmarks.md
MARKER='<!-- generated below by scripts/research/benchmark_docs.sh -->'
[ -f "$OUT/report.md" ] || { echo "no $OUT/report.md" >&2; exit 1; }
[ -f "$DOC" ] && grep -qF "$MARKER" "$DOC" || { echo "$DOC lacks the marker" >&2; exit 1; }
{
  sed "/$(printf '%s' "$MARKER" | sed 's/[][\/.*^$]/\\&/g')/q" "$DOC"
  echo
  # Drop the report's title; figures are not in the repository: name them.
  tail -n +2 "$OUT/report.md" |
    sed -E "s#^!\[[^]]*\]\((figures/[^)]*)\)#Figure: \`$OUT/\1\`  #"
} > "$DOC.tmp"
mv "$DOC.tmp" "$DOC"
echo "updated $DOC from $OUT/report.md"
