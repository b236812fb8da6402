//! `canstar conformance`: the Bosch conformance programs on the kernel.

use anyhow::Result;
use canstar::output::OutputSet;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Run only this program (baudrate, biterror, btl, crc, dlc, emlcount, extd_id,
    /// formerr, idle, overload, stuffbit, stufferr, txarb).
    #[arg(long)]
    program: Option<String>,
    /// Write one VCD per program (`<program>.vcd`) into this directory; with `--suite iso`
    /// one per case (`<case>.vcd`, the lower tester's bench from start-up through every
    /// elementary test; `<case>_2.vcd` ... for a case run on several controllers).
    #[arg(long)]
    vcd: Option<PathBuf>,
    /// Run every node in lock step with its own golden model (can-protocol.md §19): print
    /// each divergence, and count them in the final line (`N passed, M failed, K divergences`).
    #[arg(long)]
    lockstep: bool,
    #[command(flatten)]
    engine: canstar::engine::EngineArg,
    /// The suite: `bosch` (the Bosch reference programs, the default) or `iso` (the
    /// ISO 16845-1 cases implemented on the lower tester).
    #[arg(long, default_value = "bosch", value_parser = ["bosch", "iso"])]
    suite: String,
    /// With `--suite iso`: run only the cases of this clause (`7.2.2`, or `7.2` for
    /// all of 7.2) or of this case name (`iso_7_2_2_stuff_error`).
    #[arg(long)]
    case: Option<String>,
}

pub fn run(a: Args) -> Result<()> {
    if a.suite == "iso" {
        anyhow::ensure!(a.program.is_none() && !a.lockstep, "--program and --lockstep belong to the bosch suite");
        if let Some(c) = &a.case {
            let cases = canstar_verify::iso::cases();
            let names: Vec<String> = cases.iter().map(|k| format!("{} ({})", k.clause, k.name)).collect();
            anyhow::ensure!(cases.iter().any(|k| k.matches(c)), "no ISO case matches `{c}` (cases: {})", names.join(", "));
        }
        // The VCDs are staged and moved into the --vcd directory when every case ran.
        let mut set = OutputSet::new();
        let stage = a.vcd.as_deref().map(|d| set.dir(d)).transpose()?;
        let mut out = StdoutWriter;
        let (_, failed) = canstar_verify::iso::run_iso_cli_vcd(a.case.as_deref(), stage.as_deref(), &mut out)?;
        set.commit()?;
        anyhow::ensure!(failed == 0, "{failed} ISO elementary test(s) failed");
        return Ok(());
    }
    anyhow::ensure!(a.case.is_none(), "--case belongs to --suite iso");
    if let Some(p) = &a.program {
        let names: Vec<&str> = canstar_verify::conformance::programs().iter().map(|p| p.name).collect();
        anyhow::ensure!(names.contains(&p.as_str()), "unknown program `{p}` (programs: {})", names.join(", "));
    }
    // The VCDs are staged and moved into the --vcd directory when every program ran.
    let mut set = OutputSet::new();
    let stage = a.vcd.as_deref().map(|d| set.dir(d)).transpose()?;
    let mut out = StdoutWriter;
    let opts = canstar_verify::conformance::RunOptions { vcd_dir: stage, lockstep: a.lockstep, engine: a.engine.engine };
    let (_, failed, divergences) = canstar_verify::conformance::run_cli_opts(a.program.as_deref(), &opts, &mut out)?;
    set.commit()?;
    if failed > 0 || divergences > 0 {
        anyhow::bail!("{failed} conformance step(s) failed, {divergences} lock-step divergence(s)");
    }
    Ok(())
}

/// Standard output through [`outln!`]'s handling of a closed pipe.
struct StdoutWriter;

impl std::io::Write for StdoutWriter {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let mut o = std::io::stdout().lock();
        match o.write_all(buf).and_then(|()| o.flush()) {
            Ok(()) => Ok(buf.len()),
            Err(e) => super::print::closed(&e),
        }
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}
