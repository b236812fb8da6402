//! Resource figures of the ECP5 (ULX3S) and Artix-7 (Arty A7) boards: Yosys
//! `synth_ecp5` and `synth_xilinx -family xc7` of the committed hub and SJA1000
//! top succeed without latches (and without anything `check -assert` rejects);
//! the cell counts are printed (`--nocapture`) and quoted in README.md.
use canstar_hdl::flow::{self, SynthTarget};
use std::path::Path;

/// (file under verilog-out/, top module)
const DESIGNS: [(&str, &str); 2] = [("hub/canstar_hub.v", "canstar_hub"), ("controller/canstar_sja1000.v", "canstar_sja1000")];

fn synth(target: SynthTarget, flip_flop: &str) {
    for (file, top) in DESIGNS {
        let v = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("verilog-out").join(file)).unwrap();
        let r = flow::synth_check(&v, top, target).unwrap_or_else(|e| panic!("{top} ({target:?}): {e}"));
        println!("{top} {target:?}: {} cells\n{}", r.cells, r.stat);
        assert!(r.cells > 0 && r.stat.contains(flip_flop), "{top}: no {flip_flop} in\n{}", r.stat);
    }
}

#[test]
#[ignore = "needs yosys: run scripts/test-all.sh"]
fn hub_and_sja1000_synthesise_for_ecp5() {
    synth(SynthTarget::Ecp5, "TRELLIS_FF");
}

#[test]
#[ignore = "needs yosys: run scripts/test-all.sh"]
fn hub_and_sja1000_synthesise_for_artix7() {
    synth(SynthTarget::Xilinx7, "FDRE");
}
