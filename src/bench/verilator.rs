//! The Verilator column of `canstar bench`: the project's harness
//! (`models/verilator/bench.cpp`) built for a design's Verilog into a cache directory,
//! run on a recorded workload; it checks its output hash against the compiled model's.

use canstar_models::stim::{verilator_ports_h, Stim, VERILATOR_BENCH_CPP};
use canstar_models::Model;
use std::hash::{Hash, Hasher};
use std::path::PathBuf;
use std::process::Command;

/// The Verilator harness of one design.
pub struct Harness {
    exe: PathBuf,
    dir: PathBuf,
}

/// Cache directory of the harnesses (`CANSTAR_BENCH_CACHE`, else the system temp dir).
fn cache_dir() -> PathBuf {
    std::env::var_os("CANSTAR_BENCH_CACHE").map(PathBuf::from).unwrap_or_else(|| std::env::temp_dir().join("canstar-bench-verilator"))
}

fn run(cmd: &mut Command) -> Result<String, String> {
    let out = cmd.output().map_err(|e| format!("{:?}: {e}", cmd.get_program()))?;
    if out.status.success() {
        Ok(String::from_utf8_lossy(&out.stdout).into_owned())
    } else {
        let err = String::from_utf8_lossy(&out.stderr);
        Err(format!("{:?} failed: {}", cmd.get_program(), err.lines().rev().take(3).collect::<Vec<_>>().join(" / ")))
    }
}

impl Harness {
    /// Build (or find in the cache) the harness of `verilog` (top module `top`) with the
    /// port adapters of `model`. Err says why not (no `verilator`, build failure).
    pub fn build(name: &str, verilog: &str, model: &dyn Model) -> Result<Harness, String> {
        if !canstar_hdl::flow::have_tool("verilator") {
            return Err("verilator not installed".into());
        }
        let ports = verilator_ports_h(model);
        let mut h = std::collections::hash_map::DefaultHasher::new();
        (verilog, &ports, VERILATOR_BENCH_CPP).hash(&mut h);
        let dir = cache_dir().join(format!("{name}-{:016x}", h.finish()));
        let exe = dir.join("obj").join("Vtop");
        if exe.exists() {
            return Ok(Harness { exe, dir });
        }
        std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
        let w = |f: &str, t: &str| std::fs::write(dir.join(f), t).map_err(|e| e.to_string());
        w("design.v", verilog)?;
        w("ports.h", &ports)?;
        w("bench.cpp", VERILATOR_BENCH_CPP)?;
        eprintln!("building the Verilator harness of {name} in {} (once; cached)", dir.display());
        run(Command::new("verilator")
            .current_dir(&dir)
            .args(["--cc", "-O3", "--x-assign", "fast", "--x-initial", "fast", "--noassert", "-Wno-fatal", "-Wno-lint", "-Wno-UNOPTFLAT"])
            .args(["--top-module", "top", "--prefix", "Vtop", "-Mdir", "obj", "--exe", "bench.cpp"])
            .arg("-CFLAGS")
            .arg(format!("-O3 -DBENCH_TOP=Vtop -DBENCH_TOP_HEADER='\"Vtop.h\"' -I{}", dir.display()))
            .arg("design.v"))?;
        // Verilator appends its own -Os after CFLAGS: OPT_FAST sets the level it uses
        run(Command::new("make").current_dir(&dir).args(["-s", "-C", "obj", "-f", "Vtop.mk", "OPT_FAST=-O3", "OPT_SLOW=-O1"]))?;
        if !exe.exists() {
            return Err(format!("{} was not built", exe.display()));
        }
        Ok(Harness { exe, dir })
    }

    /// Replay `st` (its output hash must be `expect`, the compiled model's): CPU
    /// seconds for the whole workload.
    pub fn replay(&self, st: &Stim, expect: u64) -> Result<f64, String> {
        let f = self.dir.join(format!("stim-{}.bin", std::process::id()));
        st.save(&f).map_err(|e| e.to_string())?;
        let r = run(Command::new(&self.exe).arg(&f).arg(format!("{expect:016x}")));
        let _ = std::fs::remove_file(&f);
        let out = r.map_err(|e| format!("{e} (output differs from the compiled model?)"))?;
        // "...: S streams x C cycles, Verilator R cycles/s per stream, ..."
        let rate: f64 = out
            .split("Verilator ")
            .nth(1)
            .and_then(|s| s.split_whitespace().next())
            .and_then(|s| s.parse().ok())
            .ok_or_else(|| format!("unexpected harness output: {out}"))?;
        Ok(st.cycles as f64 * st.streams as f64 / rate)
    }
}
