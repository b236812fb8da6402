#!/usr/bin/env bash
# Three engines on the same stimulus: rust-hdl direct drive and the compiled models
# (cargo bench_print), and Verilator built from the committed Verilog (-O3, the
# C++ compiled with OPT_FAST=-O3: Verilator appends its own -Os after CFLAGS).
# Writes the workloads to target/verilator-bench, builds one harness per design
# there and runs it; each harness checks its output hash against the compiled
# model's (so Verilator and the compiled model agree on the whole workload).
set -euo pipefail
cd "$(dirname "$0")/../.."
out=target/verilator-bench
export CANSTAR_BENCH_DIR="$PWD/$out"
cargo test --release -q -p canstar-models --test bench -- --ignored --nocapture --exact bench_print_verilator_files
for spec in "can_core verilog-out/controller/canstar_can_core.v canstar_can_core" \
            "sja1000 verilog-out/controller/canstar_sja1000.v canstar_sja1000" \
            "hub verilog-out/hub/canstar_hub.v canstar_hub_core"; do
  set -- $spec
  name=$1 src=$2 top=$3
  obj="$out/$name/obj"
  rm -rf "$obj"
  verilator --cc -O3 --x-assign fast --x-initial fast --noassert -Wno-fatal -Wno-lint -Wno-UNOPTFLAT \
    --top-module "$top" --prefix Vtop -Mdir "$obj" --exe "$PWD/models/verilator/bench.cpp" \
    -CFLAGS "-O3 -DBENCH_TOP=Vtop -DBENCH_TOP_HEADER='\"Vtop.h\"' -I$PWD/$out/$name" "$src" >/dev/null
  make -s -C "$obj" -f Vtop.mk OPT_FAST="-O3" OPT_SLOW="-O1" >/dev/null
  "$obj/Vtop" "$out/$name/stim.bin" "$(cat "$out/$name/expect.txt")"
done
cargo test --release -q -p canstar-models --test bench -- --ignored --nocapture --exact bench_print
