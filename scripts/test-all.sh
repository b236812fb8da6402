#!/usr/bin/env bash
# Runs every canstar check on a fresh Debian machine:
#  - installs the open EDA tools it needs (yosys, nextpnr-ice40, icepack from fpga-icestorm,
#    iverilog, verilator) and sigrok-cli (independent CAN decoder for the sim's sigrok test)
#    when missing,
#  - runs all Rust tests, including the Verilog flow tests that plain `cargo test`
#    skips (Verilator lint, Yosys synthesis, Icarus co-simulation),
#  - checks that verilog-out/ and constraints/ match what `canstar generate` writes.
set -euo pipefail
cd "$(dirname "$0")/.."

missing=()
for tool in yosys nextpnr-ice40 icepack iverilog verilator sigrok-cli; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    # the Debian package is named after the tool, but for icepack (IceStorm)
    case "$tool" in
      icepack) missing+=(fpga-icestorm) ;;
      *) missing+=("$tool") ;;
    esac
  fi
done
if [ "${#missing[@]}" -gt 0 ]; then
  echo "== installing tools: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi
if ! python3 -c "import can" >/dev/null 2>&1; then
  echo "== installing python-can (reads the candump logs in a test; its slcan client drives the slcan top in controller/tests/slcan_pty.rs)"
  python3 -m pip install -q python-can
fi
if ! python3 -c "import serial" >/dev/null 2>&1; then
  echo "== installing pyserial (python-can's slcan interface needs it: controller/tests/slcan_pty.rs)"
  python3 -m pip install -q pyserial
fi
echo "== tools: $(yosys -V | head -1); $(nextpnr-ice40 --version 2>&1 | head -1); $(iverilog -V 2>&1 | head -1); $(verilator --version)"

# Ignored tests named diag_*, long_* and bench_print are diagnostics and
# benchmarks (they print figures, assert little): run them by name.
if cargo nextest --version >/dev/null 2>&1; then
  # cargo-nextest runs the tests of all binaries side by side (cargo test runs one
  # binary after the other, and a few long Verilog and equivalence tests would
  # keep one core idle); each test gets its own process
  echo "== cargo nextest (all tests, Verilog flow included)"
  cargo nextest run --release --workspace --no-fail-fast --run-ignored all \
    --final-status-level slow --status-level fail \
    -E 'not (test(diag_) | test(long_) | test(bench_print))'
  echo "== doc tests"
  cargo test --release --workspace --doc -q
else
  echo "== cargo test (all tests, Verilog flow included; cargo-nextest not found)"
  cargo test --release --workspace --no-fail-fast -- --include-ignored --skip diag_ --skip long_ --skip bench_print
fi

echo "== generated files are up to date"
cargo run --release -q -- generate all --check
