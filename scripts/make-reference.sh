#!/usr/bin/env bash
# Renders the Mitsuba 3 reference of a fixture scene the project adds itself
# (the shared scenes come with theirs): export through the project's exporter,
# render with Mitsuba 3 (scalar_rgb, path or volpath as the export says, box
# filter; baked textures beside the XML), write the PFM beside
# the others.  Needs `pip install mitsuba` and a built CLI (npm run build).
#   bash scripts/make-reference.sh NAME [SPP]     (test/fixtures/scenes/NAME.json)
set -euo pipefail
cd "$(dirname "$0")/.."
name=$1
spp=${2:-4096}
work=$(mktemp -d)
node bin/pathtrace.js export-mitsuba "test/fixtures/scenes/$name.json" -o "$work/$name.xml" --spp "$spp"
python3 bench/mitsuba/render.py "$work/$name.xml" --out "test/fixtures/references/$name.pfm" --spp "$spp" 2>/dev/null | tail -n 1
rm -rf "$work"
