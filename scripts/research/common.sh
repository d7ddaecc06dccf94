# The shared preamble of the research scripts. Each sources it before it
# does any work:
#
#   set -euo pipefail
#   source "$(dirname "$0")/common.sh"
#
# It changes into the repository root, so every relative path a script uses
# (and every relative value below) means "relative to the repository". Paths
# the caller typed on the command line are resolved against the caller's
# directory with from_caller. Sets (environment variable, default):
#
#   REPO       the repository root, absolute
#   CALLER_PWD the directory the script was started from
#   BUILD      the build folder (COLMAP_GCN_BUILD, build), made absolute
#   COLMAP     our `colmap` front end, $BUILD/bin/colmap (absolute, so a
#              script may change directory)
#   SHARED     the shared datasets (SHARED, ../shared/datasets)
#   THREADS    threads for COLMAP, training and evaluation (THREADS, 2)
#   SEED       the training seed (SEED, 0)
#
# A script that needs another value (ambiguous_references.sh runs Debian's
# COLMAP, COLMAP_BIN, with NUM_THREADS threads) sets it after sourcing.

CALLER_PWD="$PWD"
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$REPO"

# from_caller PATH: `realpath -m PATH` in the caller's directory.
from_caller() {
  (cd "$CALLER_PWD" && realpath -m "$1")
}

BUILD="${COLMAP_GCN_BUILD:-build}"
case "$BUILD" in /*) ;; *) BUILD="$REPO/$BUILD" ;; esac
COLMAP="$BUILD/bin/colmap"
SHARED="${SHARED:-../shared/datasets}"
THREADS="${THREADS:-2}"
SEED="${SEED:-0}"
