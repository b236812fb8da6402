//! Tests of the verification flow itself.
use canstar_hdl::drive;
use canstar_hdl::flow;
use canstar_hdl::impl_clocked;
use rand::Rng;
use rust_hdl::prelude::*;

/// A registered checker whose expression mixes `&` and `==` *with*
/// parentheses, as canstar's rules require.
#[derive(LogicBlock, Default)]
struct Careful {
    clock: Signal<In, Clock>,
    a: Signal<In, Bits<4>>,
    b: Signal<In, Bits<4>>,
    c: Signal<In, Bits<4>>,
    y: Signal<Out, Bit>,
    r: DFF<Bit>,
}
impl Logic for Careful {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, r);
        self.r.d.next = (self.a.val() & self.b.val()) == self.c.val();
        self.y.next = self.r.q.val();
    }
}
impl_clocked!(Careful);

/// The same circuit written the way rust-hdl's generator gets wrong:
/// Rust reads `a & b == c` as `(a & b) == c`, Verilog as `a & (b == c)`.
#[derive(LogicBlock, Default)]
struct Careless {
    clock: Signal<In, Clock>,
    a: Signal<In, Bits<4>>,
    b: Signal<In, Bits<4>>,
    c: Signal<In, Bits<4>>,
    y: Signal<Out, Bit>,
    r: DFF<Bit>,
}
impl Logic for Careless {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, r);
        self.r.d.next = self.a.val() & self.b.val() == self.c.val();
        self.y.next = self.r.q.val();
    }
}
impl_clocked!(Careless);

fn stim<B>(a: fn(&mut B) -> [&mut Signal<In, Bits<4>>; 3]) -> impl FnMut(&mut B, &mut rand_chacha::ChaCha8Rng, usize) {
    move |u, rng, _| {
        for s in a(u) {
            s.next = rng.gen_range(0..16u64).into();
        }
    }
}

#[test]
fn rust_model_of_precedence_blocks() {
    // In Rust both blocks compute (a & b) == c.
    let mut u = Careless::default();
    drive::init(&mut u);
    u.a.next = 0b1100.into();
    u.b.next = 0b1010.into();
    u.c.next = 0b1000.into();
    drive::cycle(&mut u);
    assert!(u.y.val());
}

#[test]
fn ports_are_found_in_declaration_order() {
    let mut u = Careful::default();
    drive::init(&mut u);
    let p = flow::ports(&u);
    let names: Vec<_> = p.iter().map(|p| (p.name.as_str(), p.bits, p.output)).collect();
    assert_eq!(names, vec![("a", 4, false), ("b", 4, false), ("c", 4, false), ("y", 1, true)]);
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn flow_passes_a_parenthesised_block() {
    let mut u = Careful::default();
    let (synth, cs) = flow::full_check(&mut u, "careful", 100_000, 1, stim(|u: &mut Careful| [&mut u.a, &mut u.b, &mut u.c]))
        .expect("flow");
    assert_eq!(cs.cycles, 100_000);
    assert!(synth.cells > 0);
}

#[test]
#[ignore = "needs iverilog: run scripts/test-all.sh"]
fn cosim_catches_unparenthesised_precedence() {
    let mut u = Careless::default();
    drive::init(&mut u);
    let v = flow::emit(&u);
    // The generator really prints the expression without parentheses ...
    assert!(v.contains("a & b == c"), "generator output changed:\n{v}");
    // ... and the co-simulation catches the difference.
    let err = flow::cosim_with_verilog(&mut u, &v, "careless", 2_000, 7, &mut stim(|u: &mut Careless| [&mut u.a, &mut u.b, &mut u.c]))
        .expect_err("co-simulation must catch the precedence difference");
    let msg = err.to_string();
    assert!(msg.contains("MISMATCH") && msg.contains("port y"), "{msg}");
}

/// A difference that shows only after Icarus' share of a long co-simulation
/// (here the first 10 000 cycles) is caught by Verilator: the careless block agrees with its model while a = b = 0
/// and c = 1, which the stimulus holds for the first 12 000 cycles.
#[test]
#[ignore = "needs iverilog and verilator: run scripts/test-all.sh"]
fn cosim_catches_a_late_difference_in_verilator() {
    let mut u = Careless::default();
    drive::init(&mut u);
    let v = flow::emit(&u);
    let mut random = stim(|u: &mut Careless| [&mut u.a, &mut u.b, &mut u.c]);
    let mut late = |u: &mut Careless, rng: &mut rand_chacha::ChaCha8Rng, i: usize| {
        if i < 12_000 {
            u.a.next = 0.into();
            u.b.next = 0.into();
            u.c.next = 1.into();
        } else {
            random(u, rng, i);
        }
    };
    let err = flow::cosim_split(&mut u, &v, "careless", 20_000, 7, &mut late, 10_000).expect_err("Verilator must catch the late difference");
    let msg = err.to_string();
    assert!(msg.contains("Verilator") && msg.contains("MISMATCH") && msg.contains("port y"), "{msg}");
    // the same Verilog passes when the run ends before the difference
    let mut early = |u: &mut Careless, _: &mut rand_chacha::ChaCha8Rng, _: usize| {
        u.a.next = 0.into();
        u.b.next = 0.into();
        u.c.next = 1.into();
    };
    let rep = flow::cosim_split(&mut u, &v, "careless", 11_000, 7, &mut early, 10_000).expect("agreeing stimulus passes");
    assert_eq!((rep.cycles, rep.iverilog_cycles, rep.verilator_cycles), (11_000, 10_000, 11_000));
}

#[test]
#[ignore = "needs yosys: run scripts/test-all.sh"]
fn synth_check_rejects_a_latch() {
    let v = "module top(input wire en, input wire d, output reg q);\n always @(*) if (en) q = d;\nendmodule\n";
    let e = flow::synth_check(v, "top", flow::SynthTarget::Generic).expect_err("latch must be rejected");
    assert!(matches!(e, flow::FlowError::Synth { .. }));
}

#[test]
#[ignore = "needs verilator: run scripts/test-all.sh"]
fn lint_rejects_a_real_warning() {
    // A multiply-driven / unused-input design gets a real lint finding that no waiver covers.
    let v = "module top(input wire a, output wire y);\n assign y = b;\nendmodule\n";
    assert!(flow::lint(v, "top").is_err());
}

#[test]
#[ignore = "needs yosys: run scripts/test-all.sh"]
fn synth_check_rejects_an_adder_with_one_signal_on_both_operands() {
    let v = "module top(input wire clk, input wire [7:0] d, output reg [7:0] q);\n \
             wire [7:0] twice = q + q;\n always @(posedge clk) q <= twice ^ d;\nendmodule\n";
    let e = flow::synth_check(v, "top", flow::SynthTarget::Generic).expect_err("q + q must be rejected");
    let msg = e.to_string();
    assert!(msg.contains("same signal on both operands"), "{msg}");
}

#[test]
#[ignore = "needs yosys: run scripts/test-all.sh"]
fn synth_check_accepts_a_shift_and_an_adder_of_two_signals() {
    let shift = "module top(input wire clk, input wire [7:0] d, output reg [7:0] q);\n \
                 always @(posedge clk) q <= (q << 1) ^ d;\nendmodule\n";
    flow::synth_check(shift, "top", flow::SynthTarget::Generic).expect("a shift is fine");
    let add = "module top(input wire clk, input wire [7:0] d, output reg [7:0] q);\n \
               always @(posedge clk) q <= q + d;\nendmodule\n";
    flow::synth_check(add, "top", flow::SynthTarget::Generic).expect("an adder of two signals is fine");
}

#[test]
fn same_operand_adders_reads_yosys_json() {
    let json = r#"{"modules":{"top":{"cells":{
        "$add$x.v:2$1":{"type":"$add","attributes":{"src":"x.v:2.15-2.20"},"connections":{"A":[2,3],"B":[2,3],"Y":[4,5]}},
        "$add$x.v:3$2":{"type":"$add","attributes":{"src":"x.v:3.15-3.20"},"connections":{"A":[2,3],"B":[6,7],"Y":[8,9]}},
        "$add$x.v:4$3":{"type":"$add","attributes":{},"connections":{"A":["0","1"],"B":["0","1"],"Y":[10,11]}},
        "$xor$x.v:5$4":{"type":"$xor","attributes":{},"connections":{"A":[2,3],"B":[2,3],"Y":[12,13]}}}}}}"#;
    assert_eq!(flow::same_operand_adders(json).unwrap(), vec!["top: x.v:2.15-2.20".to_string()]);
    assert!(flow::same_operand_adders("not json").is_err());
}
