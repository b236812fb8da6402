//! Every committed generated Verilog file lints clean and synthesises latch-free
//! under its own top-module name.
use canstar_hdl::flow;
use std::path::{Path, PathBuf};

fn verilog_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            verilog_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "v") {
            out.push(p);
        }
    }
}

#[test]
#[ignore = "needs verilator and yosys: run scripts/test-all.sh"]
fn generated_verilog_lints_and_synthesises() {
    let mut files = vec![];
    verilog_files(&Path::new(env!("CARGO_MANIFEST_DIR")).join("verilog-out"), &mut files);
    assert!(!files.is_empty());
    for f in files {
        let top = f.file_stem().unwrap().to_string_lossy().into_owned();
        let v = std::fs::read_to_string(&f).unwrap();
        // the file's top and, where there is one, its board top (active-low reset)
        let board = format!("{top}_board");
        for t in [top.clone(), board.clone()] {
            if t == board && !v.contains(&format!("module {board}(")) {
                continue;
            }
            flow::lint(&v, &t).unwrap_or_else(|e| panic!("{} ({t}): {e}", f.display()));
            flow::synth_check(&v, &t, flow::SynthTarget::Generic).unwrap_or_else(|e| panic!("{} ({t}): {e}", f.display()));
        }
    }
}
