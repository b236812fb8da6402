//! The `--engine` option shared by the simulating commands (`sim`, `conformance`,
//! `fuzz`, `campaign`, `bench`): which engine simulates the RTL.

pub use canstar_models::Engine;

/// `--engine compiled|rust-hdl`.
#[derive(clap::Args, Clone, Copy, Debug)]
pub struct EngineArg {
    /// Simulation engine of the RTL: `compiled` (the committed compiled models, default)
    /// or `rust-hdl` (the rust-hdl designs driven directly: the reference, ~100x slower).
    /// Both give the same results.
    #[arg(long, default_value_t = Engine::Compiled, value_parser = parse)]
    pub engine: Engine,
}

fn parse(s: &str) -> Result<Engine, String> {
    s.parse()
}
