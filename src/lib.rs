//! The `canstar` command-line tool's library: configuration, boards, the design
//! registry, Verilog text helpers, file generation, the resource report, iCE40
//! bitstreams and the kernel benchmark. The RTL lives in `canstar-hdl`, `canstar-controller` and
//! `canstar-hub`; the simulation in `canstar-sim` (kernel), `canstar-verify`
//! (controller verification) and `canstar-recan` (ReCANcentrate system).
//!
//! Dependencies point one way: `generate` → `designs` → `verilog`, `boards`,
//! `config`; `report` → `verilog`; `build` → `designs`, `boards`, `report`,
//! `output`; `output` (the staged, all-or-nothing writing of a command's files)
//! and `input` (bounded reads of input files) depend on nothing here.

pub mod bench;
pub mod boards;
pub mod build;
pub mod config;
pub mod designs;
pub mod engine;
pub mod generate;
pub mod input;
pub mod output;
pub mod report;
pub mod verilog;
