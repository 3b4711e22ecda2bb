#!/usr/bin/env bash
# Runs fuzz_loader over the checked-in corpus (tests/fuzz/corpus, seeds made by make_corpus.py,
# and tests/fuzz/regressions, inputs that once failed; neither is ever written to) for RUNS
# cases, new cases going to SCRATCH and crashing inputs to FINDINGS; fails when libFuzzer finds
# anything or when no case of the corpus loaded (a harness that only sees errors tests nothing).
#   run_fuzz.sh FUZZ_LOADER RUNS SCRATCH FINDINGS [libFuzzer flags...]
# ctest (fuzz.loader_corpus) and `make fuzz` call it; docs/testing.md has the details.
set -euo pipefail
bin=$1 runs=$2 scratch=$3 findings=$4
shift 4
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$scratch" "$findings"
stats="$findings/stats.txt"
SNELL_FUZZ_STATS="$stats" "$bin" -runs="$runs" -timeout=30 -rss_limit_mb=4096 -max_len=262144 \
  -dict="$here/scene.dict" -artifact_prefix="$findings/" -print_final_stats=1 "$@" "$scratch" "$here/corpus" "$here/regressions"
cat "$stats"
loaded=$(sed -n 's/.*loaded \([0-9]*\),.*/\1/p' "$stats")
if [ "${loaded:-0}" -eq 0 ]; then
  echo "run_fuzz.sh: no case loaded; is the corpus broken?" >&2
  exit 1
fi
