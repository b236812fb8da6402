//! `canstar build`: a bitstream of one role (hub, controller) for one iCE40
//! board. Everything that can be checked without the tools is checked first
//! ([`plan`]: the role, the board, its family and device, the configuration,
//! the PLL setting for the design clock, the pins); then [`run`] synthesises
//! with Yosys `synth_ice40`, places and routes with nextpnr-ice40 under the
//! watchdog of `canstar report` (seeds 1, 2, ... until one meets the PLL's clock),
//! packs with icepack and moves the files into `<out>/<board>/<role>/` together.
//! The tools work inside the output's staging folder, so a failed or
//! interrupted build leaves nothing behind.
//!
//! - [`pll`]: the iCE40 PLL setting for (board oscillator, design clock);
//! - [`top`]: the bitstream's top module around the design's board top;
//! - [`roles`]: the registry of buildable designs;
//! - [`tools`]: the tools, their packages, the device arguments.

pub mod pll;
pub mod roles;
pub mod tools;
pub mod top;

use crate::boards::pinfile::{pin_file, PinFile};
use crate::boards::{Board, DesignPins, Format};
use crate::config::Config;
use crate::output::OutputSet;
use crate::report::pnr::{Outcome, Pnr, SeedRun};
use anyhow::{bail, Context, Result};
use pll::PllSettings;
use roles::{Design, Role};
use std::path::{Path, PathBuf};
use std::time::Duration;
use top::Exposed;

/// What to build and how.
#[derive(Debug, Clone)]
pub struct Request {
    /// A built-in board name or a board .toml file.
    pub board: String,
    pub role: String,
    pub config: Config,
    /// The output folder; the files go to `<out>/<board>/<role>/`.
    pub out: PathBuf,
    /// Place-and-route seeds to try (1..=seeds), until one meets the clock.
    pub seeds: u64,
    /// Kill a seed's run after this long without router progress.
    pub stall: Duration,
    /// Time limit of one seed's run.
    pub timeout: Duration,
    /// Largest PLL error accepted, ppm.
    pub tolerance_ppm: f64,
    /// Write the bitstream even if fmax is below the design clock.
    pub timing_allow_fail: bool,
}

/// A checked build: everything but the tools' work.
pub struct Plan {
    pub board: Board,
    pub role: &'static Role,
    pub design: Design,
    pub pll: PllSettings,
    /// nextpnr-ice40's device arguments.
    pub device: Vec<String>,
    /// The bitstream's top module (`<design top>_pll`).
    pub top: String,
    /// The design's Verilog and the bitstream top.
    pub verilog: String,
    pub pcf: PinFile,
    /// `<out>/<board>/<role>`.
    pub dest: PathBuf,
}

/// Which ports of the design get pins: every functional port whole; the debug
/// outputs in order onto the free debug pins, the last one in part when the pins
/// run out inside it (never a single bit of a vector, which a PCF cannot name
/// apart from the vector), the rest not at all.
pub fn exposure(design: &Design, free_debug_pins: usize) -> Vec<Exposed> {
    let mut left = free_debug_pins;
    let mut out = vec![];
    for (name, bits, output) in &design.ports {
        // Functional ports and inputs whole (an input cannot be left open; the pin
        // file names a missing pin).
        let whole = name == "clock" || design.functional.contains(name) || !output;
        let exposed = if whole {
            *bits
        } else {
            let k = (*bits).min(left);
            let k = if *bits > 1 && k == 1 { 0 } else { k };
            left = if k < *bits { 0 } else { left - k };
            k
        };
        out.push(Exposed { name: name.clone(), bits: *bits, exposed, output: *output });
    }
    out
}

/// Check everything that needs no tool: role, board (an iCE40 board with a PCF),
/// configuration, PLL setting and pins.
pub fn plan(req: &Request) -> Result<Plan> {
    let role = roles::lookup(&req.role)?;
    let board = Board::lookup(&req.board)?;
    if board.family != "ice40" {
        bail!(
            "{}: family: bitstream not supported for family {} (canstar build makes iCE40 bitstreams with Yosys, nextpnr-ice40 and icepack; \
             `canstar generate --board {}` writes its pin files)",
            board.label(),
            board.family,
            board.name
        );
    }
    if board.format != Format::Pcf {
        bail!("{}: format: an iCE40 board needs format = \"pcf\" for nextpnr-ice40, not {:?}", board.label(), board.format.ext());
    }
    let device = tools::device_args(&board)?;
    req.config.validate()?;
    let design = (role.render)(&req.config)?;
    let pll = pll::choose(board.clock.hz, design.clock_hz, req.tolerance_ppm, &board.label())?;
    let (_, free_debug) = board.pinout(role.pinout)?;
    let exposed = exposure(&design, free_debug.len());
    let mut pins = DesignPins::default();
    for p in exposed.iter().filter(|p| p.name != "clock" && p.exposed > 0) {
        let roles = DesignPins::port_roles(&p.name, p.bits).into_iter().take(p.exposed);
        if design.functional.contains(&p.name) || !p.output {
            pins.functional.extend(roles);
        } else {
            pins.debug.extend(roles);
        }
    }
    let top = format!("{}_pll", design.top);
    let mut pcf = pin_file(&board, role.pinout, &top, &pins)?;
    if !pcf.left_out.is_empty() {
        bail!("internal: debug outputs {:?} found no pin after the exposure was computed", pcf.left_out);
    }
    pcf.text = pcf.text.replace("regenerate with `canstar generate`", &format!("regenerate with `canstar build --board {} {}`", req.board, role.name));
    let verilog = format!("{}\n{}", design.verilog, top::pll_top(&top, &design.top, &exposed, &board.clock.port, &pll)?);
    let dest = req.out.join(&board.name).join(role.name);
    Ok(Plan { board, role, design, pll, device, top, verilog, pcf, dest })
}

/// A finished build.
#[derive(Debug, Clone)]
pub struct Built {
    /// Every seed tried, in order.
    pub runs: Vec<SeedRun>,
    /// The seed whose bitstream was written, its logic cells and fmax.
    pub seed: u64,
    pub lc: usize,
    pub fmax_mhz: f64,
    /// The design clock (the PLL output), MHz.
    pub clock_mhz: f64,
    /// fmax at least the design clock.
    pub timing_pass: bool,
    /// The files written.
    pub files: Vec<PathBuf>,
    /// The bitstream among them.
    pub bin: PathBuf,
}

/// The design clock nextpnr is asked for, MHz.
fn clock_mhz(plan: &Plan) -> f64 {
    plan.pll.fout_hz() / 1e6
}

/// Run the tools and write `<dest>/<design top>.{bin,pcf,v}` and `nextpnr.log`;
/// `on_run` sees each seed's run as it ends.
pub fn run(plan: &Plan, req: &Request, on_run: &mut dyn FnMut(&SeedRun)) -> Result<Built> {
    tools::require()?;
    let mut set = OutputSet::new();
    let stage = set.dir(&plan.dest)?;
    let work = stage.join("work");
    std::fs::create_dir(&work).with_context(|| format!("cannot write into {}", plan.dest.display()))?;
    let stem = &plan.design.top;
    let (v, pcf, json) = (stage.join(format!("{stem}.v")), stage.join(format!("{stem}.pcf")), work.join("netlist.json"));
    std::fs::write(&v, &plan.verilog)?;
    std::fs::write(&pcf, &plan.pcf.text)?;
    tools::synth(&v, &plan.top, &json).with_context(|| format!("synthesis of {}", plan.top))?;
    let f = clock_mhz(plan);
    let pnr = Pnr { program: "nextpnr-ice40".into(), freq_mhz: f, stall: req.stall, timeout: req.timeout };
    let (mut runs, mut best): (Vec<SeedRun>, Option<(u64, usize, f64)>) = (vec![], None);
    for seed in 1..=req.seeds {
        let mut args = plan.device.clone();
        let arg = |p: &Path| p.display().to_string();
        args.extend(["--pcf".into(), arg(&pcf), "--json".into(), arg(&json), "--asc".into(), arg(&work.join(format!("seed{seed}.asc")))]);
        args.extend(["--seed".into(), seed.to_string(), "--freq".into(), format!("{f:.6}"), "--timing-allow-fail".into()]);
        args.extend(["--log".into(), arg(&work.join(format!("seed{seed}.log")))]);
        let r = pnr.run_args(args, seed)?;
        on_run(&r);
        if let Outcome::Placed { lc, fmax_mhz } = r.outcome {
            if best.is_none_or(|(_, _, b)| fmax_mhz > b) {
                best = Some((seed, lc, fmax_mhz));
            }
        }
        runs.push(r);
        if best.is_some_and(|(_, _, b)| b >= f) {
            break;
        }
    }
    let Some((seed, lc, fmax_mhz)) = best else {
        let why: Vec<String> = runs.iter().map(SeedRun::describe).collect();
        let hint = if why.iter().any(|w| w.contains("PLL")) {
            " (the iCE40 PLL drives the global network through the input path of its pads, on the HX8K in CB132 \
             the balls A6/A7 for the top PLL and P7/P8 for the bottom one: the pinout may use them only for outputs)"
        } else {
            ""
        };
        bail!("place and route of {} on {}: no seed placed ({}){hint}; nothing written", plan.top, plan.board.label(), why.join("; "));
    };
    let timing_pass = fmax_mhz >= f;
    if !timing_pass && !req.timing_allow_fail {
        bail!(
            "timing: fmax {fmax_mhz:.2} MHz (best of {} seed(s), seed {seed}) is below the {f:.6} MHz design clock of the PLL; \
             nothing written (--timing-allow-fail writes the bitstream anyway, --seeds tries more seeds)",
            runs.len()
        );
    }
    let bin = stage.join(format!("{stem}.bin"));
    tools::icepack(&work.join(format!("seed{seed}.asc")), &bin)?;
    let bytes = std::fs::read(&bin).with_context(|| format!("reading {}", bin.display()))?;
    if !tools::is_ice40_bitstream(&bytes) {
        bail!("icepack wrote no iCE40 bitstream (no 7E AA 99 7E synchronisation word)");
    }
    std::fs::rename(work.join(format!("seed{seed}.log")), stage.join("nextpnr.log"))?;
    std::fs::remove_dir_all(&work)?;
    let files = set.commit()?;
    let bin = plan.dest.join(format!("{stem}.bin"));
    Ok(Built { runs, seed, lc, fmax_mhz, clock_mhz: f, timing_pass, files, bin })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request(board: &str, role: &str) -> Request {
        Request {
            board: board.into(),
            role: role.into(),
            config: Config::default(),
            out: "build".into(),
            seeds: 1,
            stall: Duration::from_secs(60),
            timeout: Duration::from_secs(600),
            tolerance_ppm: pll::DEFAULT_TOLERANCE_PPM,
            timing_allow_fail: false,
        }
    }

    #[test]
    fn hub_plan_on_the_alchitry_cu() {
        let p = plan(&request("alchitry-cu", "hub")).unwrap();
        assert_eq!(p.top, "canstar_hub_pll");
        assert_eq!(p.dest, Path::new("build/alchitry-cu/hub"));
        assert_eq!(p.device, ["--hx8k", "--package", "cb132"]);
        for line in ["set_io clock P7", "set_io rst_n P8", "set_io rx[0] M1", "set_io tx[0] L1", "set_io isolated[0] J11", "set_io hub_tx[1] C5"] {
            assert!(p.pcf.text.contains(&format!("{line}\n")), "missing `{line}` in\n{}", p.pcf.text);
        }
        assert!(p.pcf.text.contains("canstar build --board alchitry-cu hub"), "{}", p.pcf.text);
        assert!(p.verilog.contains("module canstar_hub_pll(") && p.verilog.contains("GENCLK_HALF"));
        // The clock, 12 functional port bits and every debug pin (the 53 pins end
        // exactly with `dbc`, after isolated .. bic).
        let set_io = p.pcf.text.lines().filter(|l| l.starts_with("set_io ")).count();
        assert_eq!(set_io, 1 + 12 + p.board.debug.pins.len(), "{}", p.pcf.text);
        assert!(p.pcf.text.contains("set_io dbc[14] ") && !p.pcf.text.contains("set_io nack"), "{}", p.pcf.text);
    }

    #[test]
    fn controller_plan_and_errors() {
        let p = plan(&request("alchitry-cu", "controller")).unwrap();
        assert!(p.pcf.text.contains("set_io wb_dat_r[7] D10\n") && p.pcf.text.contains("set_io int_n J1\n"), "{}", p.pcf.text);
        assert!(!p.pll.half && p.verilog.contains("canstar_sja1000_board canstar_pll_design ("));
        let e = |b: &str, r: &str| plan(&request(b, r)).err().map(|e| format!("{e:#}")).unwrap_or_default();
        assert!(e("alchitry-cu", "router").contains("unknown role `router` (known roles: hub, controller, slcan)"));
        assert!(e("no-board", "hub").contains("unknown board `no-board`"));
        let x = e("arty-a7", "hub");
        assert!(x.contains("board arty-a7: family: bitstream not supported for family artix7"), "{x}");
        let mut r = request("alchitry-cu", "hub");
        r.tolerance_ppm = 100.0;
        let x = format!("{:#}", plan(&r).err().unwrap());
        assert!(x.contains("board alchitry-cu: clock.hz:") && x.contains("±100 ppm"), "{x}");
    }
}
