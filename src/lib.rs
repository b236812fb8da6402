//! The `canstar` command-line tool's library: configuration, design
//! registry and file generation. The RTL itself lives in the `canstar-hdl`,
//! `canstar-controller` and `canstar-hub` crates, the simulator in `canstar-sim`.

pub mod boards;
pub mod config;
pub mod designs;
pub mod generate;
pub mod report;
