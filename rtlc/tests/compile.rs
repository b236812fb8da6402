//! The compiler on small rust-hdl designs: what it reads, how it flattens, what it
//! refuses (with which message), loop detection, shapes. The generated code's
//! behaviour is checked against rust-hdl in the canstar-models crate.

use canstar_rtlc::collect::{collect, ProbeOp};
use canstar_rtlc::ir::{Role, Stmt};
use canstar_rtlc::{analyse, compile, fingerprint, Error, Options};
use rust_hdl::prelude::*;

/// A child with a combinational path from `a` to `y`.
#[derive(LogicBlock, Default)]
struct Inc {
    a: Signal<In, Bits<4>>,
    y: Signal<Out, Bits<4>>,
}

impl Logic for Inc {
    #[hdl_gen]
    fn update(&mut self) {
        self.y.next = self.a.val() + 1;
    }
}

/// Two children in series through the parent, a register, a constant, a loop over
/// a vector of signals.
#[derive(LogicBlock)]
struct Chain {
    clock: Signal<In, Clock>,
    x: Signal<In, Bits<4>>,
    bits: Vec<Signal<In, Bit>>,
    z: Signal<Out, Bits<4>>,
    ones: Signal<Out, Bits<4>>,
    first: Inc,
    second: Inc,
    r: DFF<Bits<4>>,
    k: Constant<Bits<4>>,
    n: Signal<Local, Bits<4>>,
}

impl Chain {
    fn new(k: u64) -> Chain {
        Chain {
            clock: Default::default(),
            x: Default::default(),
            bits: (0..3).map(|_| Default::default()).collect(),
            z: Default::default(),
            ones: Default::default(),
            first: Default::default(),
            second: Default::default(),
            r: Default::default(),
            k: Constant::new(k.into()),
            n: Default::default(),
        }
    }
}

impl Logic for Chain {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, r);
        self.first.a.next = self.x.val();
        self.second.a.next = self.first.y.val() ^ self.k.val();
        self.r.d.next = self.second.y.val();
        self.z.next = self.r.q.val();
        self.n.next = 0.into();
        for i in 0..3 {
            if self.bits[i].val() {
                self.n.next = self.n.val() + 1;
            }
        }
        self.ones.next = self.n.val();
    }
}

#[test]
fn the_hierarchy_is_read_as_rust_hdl_presents_it() {
    let h = collect(&Chain::new(3)).unwrap();
    let scopes: Vec<&str> = h.ops.iter().filter_map(|o| if let ProbeOp::Scope(n) = o { Some(n.as_str()) } else { None }).collect();
    assert_eq!(scopes, ["top", "first", "second", "r"]);
    let names: Vec<String> = h.modules[0].atoms.iter().map(|&a| h.atoms[a].name.clone()).collect();
    assert_eq!(names, ["clock", "x", "bits$0", "bits$1", "bits$2", "z", "ones", "k", "n"]);
    assert_eq!(h.atom_path(h.modules[3].atoms[1]), "r.q");
    let k = h.modules[0].atoms[7];
    assert_eq!((h.atoms[k].kind, h.atoms[k].value), (AtomKind::Constant, 3));
}

#[test]
fn the_design_is_flattened_with_roles_and_registers() {
    let (d, _) = analyse(&Chain::new(3)).unwrap();
    let role = |p: &str| d.sigs.iter().find(|s| s.path == p).unwrap_or_else(|| panic!("{p}")).role.clone();
    assert_eq!(role("x"), Role::Input);
    assert_eq!(role("k"), Role::Const);
    assert_eq!(role("clock"), Role::Clock);
    assert!(matches!(role("r.q"), Role::Reg(0)));
    assert!(matches!(role("z"), Role::Comb(_)), "outputs keep their storage");
    // pure wires became aliases: first.a is x, second.y feeds r.d directly
    assert_eq!(role("first.a"), Role::Alias(canstar_rtlc::ir::Expr::read(d.inputs[0], 4)));
    assert!(matches!(role("r.d"), Role::Alias(_)));
    assert!(d.dffs[0].clocked);
    assert_eq!(d.inputs.len(), 4);
    // the loop is unrolled: three conditional increments of the local
    let top = d.blocks.iter().find(|b| b.module == 0).unwrap();
    let ifs = top.stmts.iter().filter(|s| matches!(s, Stmt::If { .. })).count();
    assert_eq!(ifs, 3);
}

#[test]
fn a_parent_block_is_split_around_a_combinational_child() {
    let c = compile(&Chain::new(3), &Options { name: "Chain".into(), ..Default::default() }).unwrap();
    // second.a depends on first.y which depends on first.a: the parent's block cannot
    // run as one piece before or after the children
    assert!(c.stats.groups >= 3, "{:?}", c.stats);
    assert!(c.source.contains("pub struct Chain"));
    assert!(c.source.contains("pub bits_0: bool"));
    assert!(c.warnings.is_empty(), "{:?}", c.warnings);
}

/// A real combinational loop: `y` feeds `a` of the same child.
#[derive(LogicBlock, Default)]
struct Looped {
    clock: Signal<In, Clock>,
    x: Signal<In, Bits<4>>,
    z: Signal<Out, Bits<4>>,
    inc: Inc,
}

impl Logic for Looped {
    #[hdl_gen]
    fn update(&mut self) {
        self.inc.a.next = self.inc.y.val() ^ self.x.val();
        self.z.next = self.inc.y.val();
    }
}

#[test]
fn a_combinational_loop_is_reported_with_its_signals() {
    match compile(&Looped::default(), &Options::default()) {
        Err(Error::CombLoop(names)) => {
            assert!(names.iter().any(|n| n.contains("inc.a")) && names.iter().any(|n| n.contains("inc.y")), "{names:?}");
        }
        other => panic!("expected a loop, got {:?}", other.map(|c| c.stats)),
    }
}

/// A structural cycle that is not a loop on any path (as in the CAN FSM: `e` is set
/// from the child on one branch, `s` read on the other).
#[derive(LogicBlock, Default)]
struct FalsePath {
    clock: Signal<In, Clock>,
    c: Signal<In, Bit>,
    x: Signal<In, Bits<4>>,
    z: Signal<Out, Bits<4>>,
    inc: Inc,
    e: Signal<Local, Bit>,
    s: Signal<Local, Bits<4>>,
}

impl Logic for FalsePath {
    #[hdl_gen]
    fn update(&mut self) {
        self.e.next = false;
        self.s.next = self.x.val();
        if self.c.val() {
            self.e.next = self.inc.y.val() == 3;
        } else {
            if !self.e.val() {
                self.s.next = self.x.val() + 2;
            }
        }
        self.inc.a.next = self.s.val();
        self.z.next = self.inc.y.val();
        if self.e.val() {
            self.z.next = 0.into();
        }
    }
}

#[test]
fn a_false_path_is_not_a_loop() {
    let c = compile(&FalsePath::default(), &Options { name: "FalsePath".into(), ..Default::default() }).unwrap();
    assert!(c.stats.groups >= 2);
}

/// Reading a local before assigning it, when its value depends on the read.
#[derive(LogicBlock, Default)]
struct ReadBefore {
    clock: Signal<In, Clock>,
    x: Signal<In, Bits<4>>,
    z: Signal<Out, Bits<4>>,
    l: Signal<Local, Bits<4>>,
}

impl Logic for ReadBefore {
    #[hdl_gen]
    fn update(&mut self) {
        self.z.next = self.l.val();
        self.l.next = self.l.val() + self.x.val();
    }
}

#[test]
fn a_value_depending_on_itself_is_a_loop() {
    match compile(&ReadBefore::default(), &Options::default()) {
        Err(Error::CombLoop(names)) => assert!(names[0].contains("l"), "{names:?}"),
        other => panic!("expected a loop, got {:?}", other.map(|c| c.stats)),
    }
}

/// Custom Verilog that is neither DFF nor RAM.
#[derive(LogicBlock, Default)]
struct Custom {
    a: Signal<In, Bit>,
    y: Signal<Out, Bit>,
}

impl Logic for Custom {
    fn update(&mut self) {
        self.y.next = !self.a.val();
    }
    fn connect(&mut self) {
        self.y.connect();
    }
    fn hdl(&self) -> Verilog {
        Verilog::Custom("assign y = ~a;".into())
    }
}

#[derive(LogicBlock, Default)]
struct WithCustom {
    clock: Signal<In, Clock>,
    a: Signal<In, Bit>,
    y: Signal<Out, Bit>,
    inner: Custom,
}

impl Logic for WithCustom {
    #[hdl_gen]
    fn update(&mut self) {
        self.inner.a.next = self.a.val();
        self.y.next = self.inner.y.val();
    }
}

#[derive(LogicBlock, Default)]
struct WithSigned {
    clock: Signal<In, Clock>,
    a: Signal<In, Signed<8>>,
    y: Signal<Out, Signed<8>>,
}

impl Logic for WithSigned {
    #[hdl_gen]
    fn update(&mut self) {
        self.y.next = self.a.val();
    }
}

#[derive(LogicBlock, Default)]
struct NoHdl {
    a: Signal<In, Bit>,
    y: Signal<Out, Bit>,
}

impl Logic for NoHdl {
    fn update(&mut self) {
        self.y.next = self.a.val();
    }
}

#[test]
fn unsupported_constructs_are_refused_clearly() {
    let e = compile(&WithCustom::default(), &Options::default()).err().unwrap().to_string();
    assert!(e.contains("`inner`") && e.contains("custom Verilog"), "{e}");
    let e = compile(&WithSigned::default(), &Options::default()).err().unwrap().to_string();
    assert!(e.contains("Signed"), "{e}");
    let e = compile(&NoHdl::default(), &Options::default()).err().unwrap().to_string();
    assert!(e.contains("no HDL"), "{e}");
}

#[test]
fn constants_are_masked_in_the_fingerprint() {
    assert_eq!(fingerprint(&Chain::new(3)).unwrap(), fingerprint(&Chain::new(9)).unwrap());
    assert_ne!(fingerprint(&Chain::new(3)).unwrap(), fingerprint(&FalsePath::default()).unwrap());
}

#[test]
fn the_mutation_hook_swaps_one_operator() {
    let base = compile(&Chain::new(3), &Options::default()).unwrap();
    let m = compile(&Chain::new(3), &Options { mutate: Some(0), ..Default::default() }).unwrap();
    assert!(m.mutation.as_deref().unwrap().contains("->"));
    assert_ne!(base.source, m.source);
    assert!(compile(&Chain::new(3), &Options { mutate: Some(1000), ..Default::default() }).is_err());
}

/// A block with a signal nothing but probes reads (`seen`).
#[derive(LogicBlock, Default)]
struct Watched {
    clock: Signal<In, Clock>,
    a: Signal<In, Bits<4>>,
    y: Signal<Out, Bits<4>>,
    r: DFF<Bits<4>>,
    seen: Signal<Local, Bit>,
}

impl Logic for Watched {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, r);
        self.r.d.next = self.a.val();
        self.y.next = self.r.q.val();
        self.seen.next = self.a.val() == self.r.q.val();
    }
}

/// The `probe_only: &[...]` list of a generated model, as signal indices.
fn probe_only_list(source: &str) -> Vec<usize> {
    let line = source.lines().find(|l| l.trim_start().starts_with("probe_only:")).expect("probe_only in the model info");
    let inner = line.split('[').nth(1).unwrap().split(']').next().unwrap();
    inner.split(',').filter(|x| !x.trim().is_empty()).map(|x| x.trim().parse().unwrap()).collect()
}

#[test]
fn keep_evaluates_a_probe_only_signal_every_clock() {
    let (d, _) = analyse(&Watched::default()).unwrap();
    let seen = d.sigs.iter().position(|s| s.path == "seen").expect("signal `seen`");
    let plain = compile(&Watched::default(), &Options::default()).unwrap();
    assert_eq!(probe_only_list(&plain.source), vec![seen], "only `seen` is probe-only");
    let kept = compile(&Watched::default(), &Options { keep: vec!["seen".into()], ..Default::default() }).unwrap();
    assert!(probe_only_list(&kept.source).is_empty(), "kept: evaluated every clock");
    let err = compile(&Watched::default(), &Options { keep: vec!["nowhere".into()], ..Default::default() }).unwrap_err();
    assert!(err.to_string().contains("keep: no signal `nowhere`"), "{err}");
}
