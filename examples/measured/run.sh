#!/usr/bin/env bash
# The worked example of docs/measured-surfaces.md: a real AFM height map (di-3.di, see SOURCE.md)
# to wear rates, with no code:
#   1. import the instrument file (units, levelling, undefined pixels checked),
#   2. fit its spectrum (does it follow the paper's self-affine power law?),
#   3. a sliding study on periodic surface pairs that carry the map's measured spectrum
#      (study.toml: [surface] source = "spectrum"), three pairs for the intervals,
#   4. its results and figures, and the static estimate beside each sliding run,
#   5. what the other route, the map itself slid over its own copy with a taper, does at its borders
#      (taper_border_contact.py).
#
#   examples/measured/run.sh OUT [STUDY]        (about a minute on 2 cores)
#
# STUDY: another study file in place of study.toml (its map is the imported di-3/heights.npy beside
# it too), e.g. fewer surface pairs or loads for a quicker run.
#
# WEARSIM names the wearsim program (default: wearsim on the PATH); `surface import` runs the
# Python of $WEARSIM_PYTHON (default python3) with `pip install "wearsim[measured]"`, which also
# draws step 5 (with matplotlib).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
out=${1:?usage: examples/measured/run.sh OUT [STUDY]}
study=${2:-$here/study.toml}
wearsim=${WEARSIM:-wearsim}
mkdir -p "$out"
# The study reads the imported map as di-3/heights.npy beside itself.
cp "$study" "$out/study.toml"

"$wearsim" surface import "$here/di-3.di" --out "$out/di-3" --overwrite
"$wearsim" surface fit "$out/di-3/heights.npy" --length 1e-5 --out "$out/fit" --overwrite
"$wearsim" study --log run "$out/study.toml" --out "$out/study"
"$wearsim" study collect "$out/study"
"$wearsim" study plot "$out/study"
"$wearsim" estimate-check "$out/study" --out "$out/estimate-check" --overwrite
"${WEARSIM_PYTHON:-python3}" "$here/taper_border_contact.py" --map "$out/di-3/heights.npy" 1e-5 1e9 --out "$out/taper"
echo "worked example done: $out/study/figures, $out/study/results.csv, $out/estimate-check/comparison.csv, $out/taper"
