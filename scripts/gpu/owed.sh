#!/bin/bash
# The real-GPU measurements docs/performance.md records, in one call on the GPU machine (after `source
# scripts/gpu/env.sh`): every size of `drape bench --backend gpu`, and 64²–256² with the bending stencils solved
# together (the global bending step), with the springs solved together (the global stretch step) and with their coarse
# correction (solver.stretch two-level), the cantilever
# with the former, the mannequin scenes, fold at 256² with
# self-contact on, off, and off at the substeps self-contact takes, and a 64² cloth on mesh colliders of about 1k, 10k
# and 100k triangles (made by scripts/gpu/mesh-spheres.mjs), and last issue 12's scenes at 128² with self-contact, their
# crossing pairs at every 10th frame (scripts/gpu-crossings.mjs: each row printed as its scene ends, so a run cut
# short keeps the rows before). Each command has a time limit; what it printed goes to
# $OUT/NAME.txt, and its last lines to the terminal.
set -u
OUT=${OUT:-/tmp/gpu-out}; mkdir -p "$OUT"
(nvidia-smi -L; nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv; nproc) 2>&1 | tee "$OUT/machine.txt"
t() { local name=$1 limit=$2; shift 2; echo "== $name: $*"; local s0=$SECONDS; timeout "$limit" "$@" > "$OUT/$name.txt" 2>&1; local rc=$?; echo "rc=$rc $((SECONDS - s0)) s"; tail -c 1200 "$OUT/$name.txt"; echo; }
node scripts/gpu/mesh-spheres.mjs /tmp/gpu-mesh
t bench-gpu 180 node bin/drape.js bench --backend gpu --sizes 64,128,256,512,1024 --frames 120
t bench-gpu-global 120 node bin/drape.js bench --backend gpu --sizes 64,128,256 --frames 60 --set solver.bending=hinges --set solver.bendingSolve=global
t bench-gpu-stretch 90 node bin/drape.js bench --backend gpu --sizes 64,128,256 --frames 60 --set solver.stretch=global
t bench-gpu-two-level 90 node bin/drape.js bench --backend gpu --sizes 64,128,256 --frames 60 --set solver.stretch=two-level
t cantilever-gpu 60 node bin/drape.js run cantilever --backend gpu --set solver.bending=hinges --set solver.bendingSolve=global --json
for s in cape skirt; do t "$s-gpu" 30 node bin/drape.js run "$s" --backend gpu --frames 300 --json; done
t fold256-off 45 node bin/drape.js run fold --set cloth.resolution=256 --set solver.selfContact=false --backend gpu --frames 180 --json
t fold256-off-73 45 node bin/drape.js run fold --set cloth.resolution=256 --set solver.selfContact=false --set solver.substeps=73 --backend gpu --frames 180 --json
t fold256-on 75 node bin/drape.js run fold --set cloth.resolution=256 --set solver.selfContact=true --backend gpu --frames 180 --json
for m in 1k 10k 100k; do t "mesh-$m-gpu" 30 node bin/drape.js run "/tmp/gpu-mesh/mesh-$m.json" --backend gpu --frames 120 --json; done
t crossings-128 150 node scripts/gpu-crossings.mjs --faces 128 --frames 180
