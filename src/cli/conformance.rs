//! `canstar conformance`: the Bosch conformance programs on the kernel.

use anyhow::Result;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Run only this program (baudrate, biterror, btl, crc, dlc, emlcount, extd_id,
    /// formerr, idle, overload, stuffbit, stufferr, txarb).
    #[arg(long)]
    program: Option<String>,
    /// Write one VCD per program (`<program>.vcd`) into this directory.
    #[arg(long)]
    vcd: Option<PathBuf>,
    /// Run every node in lock step with its own golden model (can-protocol.md §19): print
    /// each divergence, and count them in the final line (`N passed, M failed, K divergences`).
    #[arg(long)]
    lockstep: bool,
    #[command(flatten)]
    engine: canstar::engine::EngineArg,
}

pub fn run(a: Args) -> Result<()> {
    let opts = canstar_verify::conformance::RunOptions { vcd_dir: a.vcd, lockstep: a.lockstep, engine: a.engine.engine };
    let (_, failed, divergences) = canstar_verify::conformance::run_cli_opts(a.program.as_deref(), &opts, &mut std::io::stdout())?;
    if failed > 0 || divergences > 0 {
        anyhow::bail!("{failed} conformance step(s) failed, {divergences} lock-step divergence(s)");
    }
    Ok(())
}
